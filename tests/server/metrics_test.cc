#include "server/metrics.h"

#include <gtest/gtest.h>
#include <prometheus/counter.h>
#include <time.h>

#include <string>

namespace hs {
namespace {

bool Has(const std::string& text, const std::string& line) {
  return text.find(line) != std::string::npos;
}

// Each metric adds up what it is told, by label, in the text exposition.
TEST(MetricsTest, CountsAppearInExposition) {
  Metrics metrics;
  StageStatsTable delta{};
  delta[static_cast<int>(Effect::kCollision)] = {2, 3'000'000};
  metrics.ObserveStep(0.0004, delta);
  metrics.ObserveStep(0.003, StageStatsTable{});
  metrics.AddClients(true, +1);
  metrics.AddClients(false, +1);
  metrics.AddClients(false, -1);
  metrics.AddFramesSent(5);
  metrics.AddFramesDropped(2);
  metrics.AddMissedSteps(3, /*off_cpu=*/false);
  metrics.AddMissedSteps(2, /*off_cpu=*/true);
  metrics.AddRejected("GetScene", "NOT_FOUND");
  metrics.AddRejected("GetScene", "NOT_FOUND");
  const Metrics::ToolClashCounters clash = metrics.ToolClashCountersFor("demo", "left", "right");
  clash.clashes->Increment();
  clash.seconds->Increment(0.001);
  // Asked again, the same counters.
  metrics.ToolClashCountersFor("demo", "left", "right").seconds->Increment(0.001);
  const std::string text = metrics.Text();
  EXPECT_TRUE(Has(text, "hs_step_seconds_count 2"));
  EXPECT_TRUE(Has(text, "hs_step_seconds_bucket{le=\"0.0005\"} 1"));
  EXPECT_TRUE(Has(text, "hs_effect_runs_total{effect=\"collision\"} 2"));
  EXPECT_TRUE(Has(text, "hs_effect_seconds_total{effect=\"collision\"} 0.003"));
  EXPECT_TRUE(Has(text, "hs_clients{kind=\"device\"} 1"));
  EXPECT_TRUE(Has(text, "hs_clients{kind=\"viewer\"} 0"));
  EXPECT_TRUE(Has(text, "hs_frames_sent_total 5"));
  EXPECT_TRUE(Has(text, "hs_frames_dropped_total 2"));
  EXPECT_TRUE(Has(text, "hs_missed_steps_total 5"));
  EXPECT_TRUE(Has(text, "hs_missed_steps_off_cpu_total 2"));
  EXPECT_TRUE(Has(text, "hs_rejected_requests_total{code=\"NOT_FOUND\",method=\"GetScene\"} 2"));
  EXPECT_TRUE(
      Has(text, "hs_tool_clashes_total{scene=\"demo\",tool_a=\"left\",tool_b=\"right\"} 1"));
  EXPECT_TRUE(Has(text,
                  "hs_tool_clash_seconds_total{scene=\"demo\",tool_a=\"left\",tool_b=\"right\"} "
                  "0.002"));
}

double ProcessCpuSeconds() {
  timespec cpu{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &cpu);
  return static_cast<double>(cpu.tv_sec) + 1e-9 * static_cast<double>(cpu.tv_nsec);
}

// process_cpu_seconds_total is the process's CPU time when scraped: it lies
// between the process's own clock read before and after the scrape.
TEST(MetricsTest, ProcessCpuSecondsAreTheProcesssCpuTime) {
  Metrics metrics;
  const std::string name = "process_cpu_seconds_total ";
  const double before = ProcessCpuSeconds();
  const std::string text = metrics.Text();
  const double after = ProcessCpuSeconds();
  const size_t at = text.find("\n" + name);
  ASSERT_NE(at, std::string::npos) << text;
  const double scraped = std::stod(text.substr(at + 1 + name.size()));
  // The exposition prints the value with at most 1e-9 relative rounding.
  EXPECT_GE(scraped, before * (1 - 1e-9));
  EXPECT_LE(scraped, after * (1 + 1e-9));
  EXPECT_TRUE(Has(text, "# TYPE process_cpu_seconds_total counter"));
}

// An address it cannot listen on is an error, not an exception.
TEST(MetricsTest, BadAddressIsAnError) {
  Metrics metrics;
  EXPECT_FALSE(metrics.Expose("256.0.0.1:1").ok());
}

}  // namespace
}  // namespace hs

#include "client/loadtest/prometheus_text.h"

#include <gtest/gtest.h>

namespace hs::cli {
namespace {

// A hand-written exposition as a server's /metrics serves it: comments,
// a metric whose name begins with another's, labelled series (a quoted
// '}' and an escaped quote in a label value), a timestamp, blank lines.
constexpr char kSample[] =
    R"(# HELP process_cpu_seconds_total Total user and system CPU time spent in seconds.
# TYPE process_cpu_seconds_total counter
process_cpu_seconds_total 12.34

# HELP process_cpu_seconds_total_other Not the one.
process_cpu_seconds_total_other 99
# TYPE hs_effect_seconds_total counter
hs_effect_seconds_total{effect="force"} 1.5
hs_effect_seconds_total{effect="fri}c\"tion",x="y"} 2.25 1700000000000
hs_step_seconds_bucket{le="+Inf"} 7
hs_frames_sent_total 3e3
)";

// The value of a plain series is read as written.
TEST(PrometheusTextTest, PlainSeries) {
  const absl::StatusOr<double> cpu = PrometheusValue(kSample, "process_cpu_seconds_total");
  ASSERT_TRUE(cpu.ok()) << cpu.status();
  EXPECT_EQ(*cpu, 12.34);
  EXPECT_EQ(*PrometheusValue(kSample, "hs_frames_sent_total"), 3000);
  EXPECT_EQ(*PrometheusValue(kSample, "hs_step_seconds_bucket"), 7);
}

// Labelled series are summed, whatever their label values hold and with
// or without a timestamp.
TEST(PrometheusTextTest, LabelledSeriesSummed) {
  EXPECT_EQ(*PrometheusValue(kSample, "hs_effect_seconds_total"), 3.75);
}

// A metric with no sample (only a longer name begins with it) is
// NOT_FOUND; a sample that does not parse is INVALID_ARGUMENT quoting it.
TEST(PrometheusTextTest, MissingAndMalformed) {
  EXPECT_EQ(PrometheusValue(kSample, "process_cpu").status().code(), absl::StatusCode::kNotFound);
  EXPECT_EQ(PrometheusValue("# process_cpu_seconds_total 1\n", "process_cpu_seconds_total")
                .status()
                .code(),
            absl::StatusCode::kNotFound);
  for (const char* bad : {"process_cpu_seconds_total abc\n", "process_cpu_seconds_total{} \n",
                          "process_cpu_seconds_total{a=\"}\" 3\n",
                          "process_cpu_seconds_total 3 4 5\n", "process_cpu_seconds_total 3 x\n"}) {
    const absl::StatusOr<double> value = PrometheusValue(bad, "process_cpu_seconds_total");
    EXPECT_EQ(value.status().code(), absl::StatusCode::kInvalidArgument) << bad;
    EXPECT_NE(value.status().message().find("process_cpu_seconds_total"), std::string::npos);
  }
}

}  // namespace
}  // namespace hs::cli

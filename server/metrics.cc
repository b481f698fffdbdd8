#include "server/metrics.h"

#include <time.h>

#include <map>

#include <prometheus/collectable.h>
#include <prometheus/counter.h>
#include <prometheus/exposer.h>
#include <prometheus/gauge.h>
#include <prometheus/histogram.h>
#include <prometheus/registry.h>
#include <prometheus/text_serializer.h>

#include "absl/strings/str_cat.h"

namespace hs {
namespace {

// The process metric Prometheus clients export by convention, which
// prometheus-cpp leaves out: the process's CPU time (every thread, user and
// system), read at each scrape. The load test reads a remote server's CPU
// from it.
class ProcessCpu : public prometheus::Collectable {
 public:
  std::vector<prometheus::MetricFamily> Collect() const override {
    timespec cpu{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &cpu);
    prometheus::ClientMetric seconds;
    seconds.counter.value =
        static_cast<double>(cpu.tv_sec) + 1e-9 * static_cast<double>(cpu.tv_nsec);
    return {{.name = "process_cpu_seconds_total",
             .help = "Total user and system CPU time spent in seconds.",
             .type = prometheus::MetricType::Counter,
             .metric = {seconds}}};
  }
};

}  // namespace

Metrics::Metrics()
    : registry_(std::make_shared<prometheus::Registry>()),
      process_(std::make_shared<ProcessCpu>()) {
  using namespace prometheus;
  // From 50 us to 20 ms: the 1 kHz budget is 1 ms.
  step_seconds_ = &BuildHistogram()
                       .Name("hs_step_seconds")
                       .Help("Wall time of one simulation step")
                       .Register(*registry_)
                       .Add({}, Histogram::BucketBoundaries{50e-6, 100e-6, 200e-6, 500e-6, 1e-3,
                                                            2e-3, 5e-3, 10e-3, 20e-3});
  auto& effect_seconds = BuildCounter()
                             .Name("hs_effect_seconds_total")
                             .Help("Wall time spent in each effect (stage)")
                             .Register(*registry_);
  auto& effect_runs = BuildCounter()
                          .Name("hs_effect_runs_total")
                          .Help("Runs of each effect (stage)")
                          .Register(*registry_);
  for (int i = 0; i < kNumEffects; ++i) {
    const std::string name(EffectName(static_cast<Effect>(i)));
    effect_seconds_[i] = &effect_seconds.Add({{"effect", name}});
    effect_runs_[i] = &effect_runs.Add({{"effect", name}});
  }
  missed_steps_ = &BuildCounter()
                       .Name("hs_missed_steps_total")
                       .Help("Steps started more than one step late")
                       .Register(*registry_)
                       .Add({});
  missed_steps_off_cpu_ =
      &BuildCounter()
           .Name("hs_missed_steps_off_cpu_total")
           .Help(
               "Missed steps while the stepping thread was kept off the CPU, not stepping "
               "(the rule: server/step_pacer.h)")
           .Register(*registry_)
           .Add({});
  auto& clients = BuildGauge().Name("hs_clients").Help("Open streams by kind").Register(*registry_);
  devices_ = &clients.Add({{"kind", "device"}});
  viewers_ = &clients.Add({{"kind", "viewer"}});
  frames_sent_ = &BuildCounter()
                      .Name("hs_frames_sent_total")
                      .Help("Frames written to streams")
                      .Register(*registry_)
                      .Add({});
  frames_dropped_ = &BuildCounter()
                         .Name("hs_frames_dropped_total")
                         .Help("Frames dropped because a stream read too slowly")
                         .Register(*registry_)
                         .Add({});
  recorded_bytes_ = &BuildCounter()
                         .Name("hs_recorded_bytes_total")
                         .Help("Bytes written to session recordings")
                         .Register(*registry_)
                         .Add({});
  recording_skipped_steps_ = &BuildCounter()
                                  .Name("hs_recording_skipped_steps_total")
                                  .Help(
                                      "Steps left out of recordings: the recorder's queue was "
                                      "full or the disk refused")
                                  .Register(*registry_)
                                  .Add({});
  rejected_ = &BuildCounter()
                   .Name("hs_rejected_requests_total")
                   .Help("Requests that failed, by method and status code")
                   .Register(*registry_);
  agones_requests_ = &BuildCounter()
                          .Name("hs_agones_sdk_requests_total")
                          .Help("Requests to the Agones SDK, by call and result (ok, error)")
                          .Register(*registry_);
  agones_up_ = &BuildGauge()
                    .Name("hs_agones_sdk_up")
                    .Help("1 while the Agones SDK answered the last request, else 0")
                    .Register(*registry_)
                    .Add({});
  tool_clashes_ = &BuildCounter()
                       .Name("hs_tool_clashes_total")
                       .Help("Times two tools of a scene began to touch, by scene and tool pair")
                       .Register(*registry_);
  tool_clash_seconds_ = &BuildCounter()
                             .Name("hs_tool_clash_seconds_total")
                             .Help("Simulated time two tools of a scene touched, by scene and pair")
                             .Register(*registry_);
}

Metrics::~Metrics() = default;

absl::Status Metrics::Expose(const std::string& address) {
  try {
    exposer_ = std::make_unique<prometheus::Exposer>(address);
  } catch (const std::exception& e) {
    return absl::UnavailableError(absl::StrCat("metrics on ", address, ": ", e.what()));
  }
  exposer_->RegisterCollectable(registry_);
  exposer_->RegisterCollectable(process_);
  return absl::OkStatus();
}

void Metrics::ObserveStep(double step_s, const StageStatsTable& stats_delta) {
  step_seconds_->Observe(step_s);
  for (int i = 0; i < kNumEffects; ++i) {
    if (stats_delta[i].runs == 0) continue;
    effect_runs_[i]->Increment(static_cast<double>(stats_delta[i].runs));
    effect_seconds_[i]->Increment(1e-9 * static_cast<double>(stats_delta[i].total_ns));
  }
}

void Metrics::AddMissedSteps(int64_t n, bool off_cpu) {
  missed_steps_->Increment(static_cast<double>(n));
  if (off_cpu) missed_steps_off_cpu_->Increment(static_cast<double>(n));
}

void Metrics::AddClients(bool device, int delta) {
  (device ? devices_ : viewers_)->Increment(delta);
}

void Metrics::AddFramesSent(int64_t n) { frames_sent_->Increment(static_cast<double>(n)); }

void Metrics::AddFramesDropped(int64_t n) { frames_dropped_->Increment(static_cast<double>(n)); }

void Metrics::AddRecordedBytes(int64_t n) { recorded_bytes_->Increment(static_cast<double>(n)); }

void Metrics::AddRecordingSkippedSteps(int64_t n) {
  recording_skipped_steps_->Increment(static_cast<double>(n));
}

void Metrics::AddRejected(const std::string& method, const std::string& code) {
  rejected_->Add({{"method", method}, {"code", code}}).Increment();
}

void Metrics::AddAgonesRequest(const std::string& call, bool ok) {
  agones_requests_->Add({{"call", call}, {"result", ok ? "ok" : "error"}}).Increment();
  agones_up_->Set(ok ? 1 : 0);
}

Metrics::ToolClashCounters Metrics::ToolClashCountersFor(const std::string& scene,
                                                         const std::string& tool_a,
                                                         const std::string& tool_b) {
  const std::map<std::string, std::string> labels = {
      {"scene", scene}, {"tool_a", tool_a}, {"tool_b", tool_b}};
  return {&tool_clashes_->Add(labels), &tool_clash_seconds_->Add(labels)};
}

std::string Metrics::Text() const {
  std::vector<prometheus::MetricFamily> families = registry_->Collect();
  for (prometheus::MetricFamily& family : process_->Collect())
    families.push_back(std::move(family));
  return prometheus::TextSerializer().Serialize(families);
}

}  // namespace hs

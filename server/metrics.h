#pragma once
// The server's Prometheus metrics (prometheus-cpp): step time, per-effect
// time, clients, frames sent and dropped, rejected requests, and the
// process's CPU time (process_cpu_seconds_total). Exposed over
// HTTP at /metrics when an address is given. Thread-safe.

#include <array>
#include <memory>
#include <string>

#include "absl/status/statusor.h"
#include "common/sim/step_frame.h"

namespace prometheus {
class Collectable;
class Counter;
class Exposer;
class Gauge;
class Histogram;
class Registry;
template <typename T>
class Family;
}  // namespace prometheus

namespace hs {

class Metrics {
 public:
  /// Metrics kept in memory only.
  Metrics();
  ~Metrics();

  /// Serves /metrics on `address` ("127.0.0.1:9464"). INVALID_ARGUMENT or
  /// UNAVAILABLE when it cannot listen there.
  absl::Status Expose(const std::string& address);

  /// One step took `step_s` seconds (wall time); `stats_delta` is what each
  /// stage added to its counters during it.
  void ObserveStep(double step_s, const StageStatsTable& stats_delta);
  /// `n` steps missed, with the stepping thread off the CPU if `off_cpu`
  /// (server/step_pacer.h states the rule).
  void AddMissedSteps(int64_t n, bool off_cpu);
  /// A device (Interact) or viewer (Watch) stream opened (+1) or closed (-1).
  void AddClients(bool device, int delta);
  void AddFramesSent(int64_t n);
  void AddFramesDropped(int64_t n);
  /// Recording: bytes written, and steps the recorder skipped (queue full
  /// or the disk refused).
  void AddRecordedBytes(int64_t n);
  void AddRecordingSkippedSteps(int64_t n);
  /// A request of `method` failed with status `code` (a gRPC code name).
  void AddRejected(const std::string& method, const std::string& code);
  /// A request to the Agones SDK (`call`: ready, health, label, allocate,
  /// shutdown) answered (ok) or failed; the SDK counts as up while its
  /// last request was answered.
  void AddAgonesRequest(const std::string& call, bool ok);

  /// The counters of tools `tool_a` and `tool_b` of scene `scene`: the
  /// times they began to touch, and the simulated seconds they touched.
  /// Registered on first use (it allocates); the stepping thread keeps
  /// them, so that a step only increments.
  struct ToolClashCounters {
    prometheus::Counter* clashes = nullptr;
    prometheus::Counter* seconds = nullptr;
  };
  ToolClashCounters ToolClashCountersFor(const std::string& scene, const std::string& tool_a,
                                         const std::string& tool_b);

  /// The text exposition of every metric (as /metrics serves it).
  std::string Text() const;

 private:
  std::shared_ptr<prometheus::Registry> registry_;
  // process_cpu_seconds_total, collected beside the registry.
  std::shared_ptr<prometheus::Collectable> process_;
  std::unique_ptr<prometheus::Exposer> exposer_;
  prometheus::Histogram* step_seconds_;
  std::array<prometheus::Counter*, kNumEffects> effect_seconds_;
  std::array<prometheus::Counter*, kNumEffects> effect_runs_;
  prometheus::Counter* missed_steps_;
  prometheus::Counter* missed_steps_off_cpu_;
  prometheus::Gauge* devices_;
  prometheus::Gauge* viewers_;
  prometheus::Counter* frames_sent_;
  prometheus::Counter* frames_dropped_;
  prometheus::Counter* recorded_bytes_;
  prometheus::Counter* recording_skipped_steps_;
  prometheus::Family<prometheus::Counter>* rejected_;
  prometheus::Family<prometheus::Counter>* agones_requests_;
  prometheus::Gauge* agones_up_;
  prometheus::Family<prometheus::Counter>* tool_clashes_;
  prometheus::Family<prometheus::Counter>* tool_clash_seconds_;
};

}  // namespace hs

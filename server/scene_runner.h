#pragma once
// One running scene: the spec it was built from, its simulation, and the
// thread (scene-step) that steps it with the latest device poses, when
// its StepPacer says (the clock rules, and what a missed step is, are
// stated there). Its parts: the StreamRegistry of attached streams and
// their poses, and the FrameFanOut that hands each step's frame to them
// on a second thread, so that no step waits on gRPC.
// hs::Scene is not thread-safe: only the runner's thread steps it; requests
// reach it through the runner, never by touching the Scene.

#include <condition_variable>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "absl/status/statusor.h"
#include "common/api/scene_file.h"
#include "haptics/v1/scene.pb.h"
#include "haptics/v1/scene_service.pb.h"
#include "server/frame_fan_out.h"
#include "server/metrics.h"
#include "server/priority_inheriting_mutex.h"
#include "server/recording/session_recorder.h"
#include "server/snapshot_pool.h"
#include "server/step_snapshot.h"
#include "server/stream_registry.h"

namespace hs {

/// A runner's state for SceneService.GetScene.
struct RunnerInfo {
  haptics::v1::SceneSpec spec;
  int64_t step = 0;
  int64_t triangles = 0;
  int64_t revision = 0;
  int devices = 0;
  int viewers = 0;
  std::vector<std::string> claimed_tools;
};

/// How a runner steps and minds its devices.
struct RunnerOptions {
  /// SCHED_FIFO priority of the stepping threads, 0: the default scheduler
  /// (as far as the system allows: see CheckRealtimePriority).
  int realtime_priority = 0;
  /// A device that sends no pose for this long (seconds; 0: never) is
  /// ended DEADLINE_EXCEEDED and its tool released; the tool stays where
  /// its last pose put it.
  double device_timeout_s = 2.0;
};

class SceneRunner {
 public:
  /// Starts stepping `scene`, built from `spec`, on a thread. `metrics`
  /// outlives the runner.
  /// `recorder`, when given, records the session from the runner's
  /// first step (server/recording/session_recorder.h).
  SceneRunner(haptics::v1::SceneSpec spec, LoadedScene scene, Metrics& metrics,
              const RunnerOptions& options = {},
              std::unique_ptr<SessionRecorder> recorder = nullptr);
  /// Stop(UNAVAILABLE) if not stopped yet.
  ~SceneRunner();
  SceneRunner(const SceneRunner&) = delete;
  SceneRunner& operator=(const SceneRunner&) = delete;

  /// Runs one last step, sends it, ends every stream with `status` and
  /// stops the thread. Later calls do nothing.
  void Stop(const absl::Status& status);

  /// Lets `sink` drive the claimed tool and receive every frame; the
  /// scene computes the claim's needs (with prerequisites) from now on.
  /// NOT_FOUND when there is no such tool, FAILED_PRECONDITION when
  /// another device holds it (with `take_over`: that device's stream ends
  /// with that status instead), UNAVAILABLE when stopped.
  absl::Status AttachDevice(FrameSink* sink, const DeviceClaim& claim,
                            const absl::Status* take_over = nullptr);
  /// Lets `sink` receive every frame. UNAVAILABLE when stopped.
  absl::Status AttachViewer(FrameSink* sink, EffectSet needs);
  /// Stops sending to `sink` and releases its tool. When it returns, no
  /// Offer or Close to `sink` is running or will run.
  void Detach(FrameSink* sink);

  /// The device pose of `sink`'s tool for the next step (latest wins). The
  /// pose was validated by the caller.
  /// `model`: what the device asks of its local model (ToolPose's
  /// model_stale and validity_radius_m, validated by the caller too).
  void SetDevicePose(FrameSink* sink, const Isometry3d& X_WD, const AppliedPose& stamp,
                     const LocalModelRequest& model = {});

  /// The spec the scene runs now.
  haptics::v1::SceneSpec spec() const;
  /// Replaces the scene by `scene`, built from `spec`, between two steps;
  /// tools keep their device poses. FAILED_PRECONDITION (and no change)
  /// when a tool held by a device is missing from `scene`.
  absl::Status Replace(haptics::v1::SceneSpec spec, LoadedScene scene);

  RunnerInfo Info() const;
  /// The scene's name, which never changes.
  const std::string& name() const { return name_; }
  /// The streams attached now (without Info's copy of the spec).
  StreamRegistry::Counts stream_counts() const { return streams_.counts(); }
  /// Every object's mesh at the current revision (SceneService.GetGeometry).
  void Geometry(haptics::v1::SceneGeometry* out) const;
  double step_s() const { return step_s_; }

 private:
  void Run(int realtime_priority);
  // Ends the devices silent for longer than the timeout (RunnerOptions).
  void EndSilentDevices();
  // Returns the step's wall time, nanoseconds (workers included).
  int64_t StepOnce(int64_t start_lag_ns);
  // Records a stream's attach or detach ("" tool: a viewer), if recording.
  void RecordStream(bool attached, const std::string& tool, EffectSet needs);
  // Wakes the stepping thread when `change` says every device has sent.
  void WakeIfDevicesFresh(const StreamChange& change);
  // Aborts when a stream calls back from its Offer or Close (FrameSink).
  static void CheckNotInSinkCall();

  Metrics& metrics_;
  const double step_s_;
  const double device_timeout_s_;
  const absl::Status device_timeout_status_;
  const std::string name_;

  // The simulation; only the runner's thread steps it, Replace swaps it.
  // Held while the registry is asked for the step's poses or re-mapped, so
  // that tool ids always name the scene's tools (server/lock_order.h).
  mutable PriorityInheritingMutex scene_mu_{LockLevel::kScene};
  haptics::v1::SceneSpec spec_;
  LoadedScene loaded_;
  std::shared_ptr<const std::vector<std::string>> names_;
  int64_t revision_ = 0;
  int64_t step_ = 0;
  StageStatsTable last_stats_{};
  std::vector<std::optional<PendingPose>> applied_;  // by ObjectId
  // The /metrics counters of each tool pair that clashed, by (tool_a,
  // tool_b) of the scene running now.
  std::map<std::pair<ObjectId, ObjectId>, Metrics::ToolClashCounters> clash_counters_;

  // What wakes the stepping thread: a stop, or every device having sent a
  // pose since the last take (StreamChange::devices_fresh_since).
  PriorityInheritingMutex wake_mu_{LockLevel::kWake};
  std::condition_variable_any wake_cv_;
  bool stop_ = false;
  absl::Status stop_status_;
  uint64_t devices_fresh_since_ = 0;   // the latest take after which every device sent
  uint64_t last_take_ = 1;             // FreshPoses::generation of the last step's take
  int64_t missed_steps_ = 0;           // runner thread only
  int64_t missed_steps_off_cpu_ = 0;   // runner thread only
  FreshPoses fresh_;                   // runner thread only
  SnapshotPool snapshots_;             // runner thread only
  std::vector<std::string> released_;  // runner thread only: tools of silent devices

  // Told of every step, edit and stream change, in order (under scene_mu_).
  std::unique_ptr<SessionRecorder> recorder_;
  StreamRegistry streams_;
  FrameFanOut fan_out_;
  std::thread thread_;
};

}  // namespace hs

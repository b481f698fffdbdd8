#pragma once
// One running scene: the spec it was built from, its simulation, and the
// thread that steps it at the scene's rate with the latest device poses.
// Devices clock the steps: once every attached device has sent a pose since
// the last step, the next step runs at once (but not sooner than 3/4 of a
// period after the last), so a pose waits for no tick; the deadline after
// such a step leaves a quarter period for a late device. Without devices
// the scene steps on its own period.
// Frames go to the streams from a second thread (scene-frames), so that no
// step waits on gRPC.
// hs::Scene is not thread-safe: only the runner's thread steps it; requests
// reach it through the runner's mutexes, never by touching the Scene.

#include <condition_variable>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "absl/status/statusor.h"
#include "common/api/scene_file.h"
#include "haptics/v1/scene.pb.h"
#include "server/metrics.h"
#include "server/priority_inheriting_mutex.h"
#include "server/step_snapshot.h"

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

class SceneRunner {
 public:
  /// Starts stepping `scene`, built from `spec`, on a thread under
  /// SCHED_FIFO at `realtime_priority` when it is not 0 (as far as the
  /// system allows: see CheckRealtimePriority). `metrics` outlives the
  /// runner.
  SceneRunner(haptics::v1::SceneSpec spec, LoadedScene scene, Metrics& metrics,
              int realtime_priority = 0);
  /// Stop(UNAVAILABLE) if not stopped yet.
  ~SceneRunner();
  SceneRunner(const SceneRunner&) = delete;
  SceneRunner& operator=(const SceneRunner&) = delete;

  /// Runs one last step, sends it, ends every stream with `status` and
  /// stops the thread. Later calls do nothing.
  void Stop(const absl::Status& status);

  /// Lets `sink` drive tool `tool` and receive every frame; the scene
  /// computes `needs` (with prerequisites) from now on. NOT_FOUND when
  /// there is no such tool, FAILED_PRECONDITION when another device holds
  /// it, UNAVAILABLE when stopped.
  absl::Status AttachDevice(FrameSink* sink, const std::string& tool, EffectSet needs);
  /// Lets `sink` receive every frame. UNAVAILABLE when stopped.
  absl::Status AttachViewer(FrameSink* sink, EffectSet needs);
  /// Stops sending to `sink` and releases its tool. When it returns, no
  /// Offer or Close to `sink` is running or will run.
  void Detach(FrameSink* sink);

  /// The device pose of `sink`'s tool for the next step (latest wins). The
  /// pose was validated by the caller.
  void SetDevicePose(FrameSink* sink, const Isometry3d& X_WD, const AppliedPose& stamp);

  /// The spec the scene runs now.
  haptics::v1::SceneSpec spec() const;
  /// Replaces the scene by `scene`, built from `spec`, between two steps;
  /// tools keep their device poses. FAILED_PRECONDITION (and no change)
  /// when a tool held by a device is missing from `scene`.
  absl::Status Replace(haptics::v1::SceneSpec spec, LoadedScene scene);

  RunnerInfo Info() const;
  double step_s() const { return step_s_; }

 private:
  struct Attached {
    std::string tool;  // empty for viewers
    EffectSet needs;
  };
  struct PendingPose {
    Isometry3d X_WD;
    AppliedPose stamp;
    bool fresh = false;
  };

  void Run(int realtime_priority);
  // Hands each step's frame to the streams, in step order, off the
  // stepping thread: a stream's write can wait on gRPC's locks for
  // milliseconds, and a step must not.
  void FanOut(int realtime_priority);
  // Lets FanOut hand over the frames queued, then joins it.
  void StopFanOut();
  // Returns the step's wall time, nanoseconds (workers included).
  int64_t StepOnce(int64_t start_lag_ns);
  EffectSet NeedsLocked() const;
  // Whether every attached device has a pose the last step did not apply.
  bool DevicesFreshLocked() const;

  Metrics& metrics_;
  const double step_s_;

  // The simulation; only the runner's thread steps it, Replace swaps it.
  mutable PriorityInheritingMutex scene_mu_;
  haptics::v1::SceneSpec spec_;
  LoadedScene loaded_;
  std::shared_ptr<const std::vector<std::string>> names_;
  int64_t revision_ = 0;
  int64_t step_ = 0;
  StageStatsTable last_stats_{};
  std::map<std::string, PendingPose> applied_;  // by tool name

  // What the streams send and need.
  mutable PriorityInheritingMutex io_mu_;
  std::map<FrameSink*, Attached> sinks_;
  std::map<std::string, PendingPose> pending_;  // by tool name
  bool stopping_ = false;

  // Taken after io_mu_ when both are held.
  PriorityInheritingMutex stop_mu_;
  std::condition_variable_any stop_cv_;  // stop_ or devices_fresh_ set
  bool stop_ = false;
  bool devices_fresh_ = false;  // DevicesFreshLocked() held at the last pose
  absl::Status stop_status_;
  std::thread thread_;
  int64_t missed_steps_ = 0;          // runner thread only
  int64_t missed_steps_off_cpu_ = 0;  // runner thread only

  // Frames stepped and not yet handed to the streams, oldest first. Past
  // kMaxQueuedFrames (the hand-over stalled for that many steps) the
  // oldest is dropped and counted in the metrics.
  static constexpr size_t kMaxQueuedFrames = 64;
  PriorityInheritingMutex fanout_mu_;
  std::condition_variable_any fanout_cv_;
  std::deque<std::shared_ptr<const StepSnapshot>> fanout_queue_;
  bool fanout_stop_ = false;
  std::thread fanout_thread_;
  // Held by scene-frames while it offers a frame, and taken by Detach once
  // the sink is out of sinks_: so io_mu_, which the stepping thread needs,
  // is never held across a stream's write. Taken before io_mu_ when both
  // are held.
  PriorityInheritingMutex offer_mu_;
  std::vector<FrameSink*> offer_to_;  // scene-frames only
};

}  // namespace hs

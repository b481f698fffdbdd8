#pragma once
// What a scene's runner hands to its streams after each step: one shared,
// read-only copy of the step's frame with the server-side extras.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "common/sim/effects.h"
#include "common/sim/local_model_request.h"
#include "common/sim/step_frame.h"

namespace hs {

/// The latest device pose applied to one tool.
struct AppliedPose {
  /// The ToolPose's sequence; 0 before the first.
  uint64_t sequence = 0;
  /// The ToolPose's device clock, nanoseconds.
  int64_t device_time_ns = 0;
};

/// A device pose applied just before a step.
struct AppliedInput {
  ObjectId tool = -1;
  Isometry3d X_WD = Isometry3d::Identity();
  AppliedPose stamp;
  /// The first pose of a device that had just taken the tool.
  bool seat = false;
  /// What the device asked of the tool's local model with the pose.
  LocalModelRequest model;
};

class FrameSink;

/// Who holds one tool: the device's stream, and its holder's name
/// (Caller::name) as frames name it.
struct ToolHolder {
  const FrameSink* sink = nullptr;  // none: no device holds the tool
  std::string name{};
  bool operator==(const ToolHolder&) const = default;
};

/// Who holds each tool, by ObjectId of the scene that stepped.
using ToolHolders = std::vector<ToolHolder>;

struct StepSnapshot {
  /// The runner's step id: 1 for the first step, +1 per step, across scene
  /// rebuilds (StepFrame::step restarts when the scene is rebuilt).
  int64_t step = 0;
  /// Simulated time at the end of the step, seconds.
  double time_s = 0;
  /// The simulation's frame; its tool and object ids index `names`.
  StepFrame frame;
  /// Object names by ObjectId (shared until the scene is rebuilt).
  std::shared_ptr<const std::vector<std::string>> names;
  /// Per entry of frame.tools: the last device pose applied to it.
  std::vector<AppliedPose> applied;
  /// Who held each tool at the step (shared until a device comes or goes).
  std::shared_ptr<const ToolHolders> holders;
  /// The device poses applied just before this step, and the effects it
  /// was asked for (what a recording needs to re-run it).
  std::vector<AppliedInput> inputs;
  EffectSet needs;
  /// Wall time of the step, and how late it started, nanoseconds.
  int64_t step_ns = 0;
  int64_t start_lag_ns = 0;
  /// Steps missed since the runner began, and those of them missed while
  /// the stepping thread was off the CPU (server/step_pacer.h states both).
  int64_t missed_steps = 0;
  int64_t missed_steps_off_cpu = 0;
};

/// A frame's scene time may fall this far short of a due time and still be
/// due: step times are multiples of the step, computed in floating point.
inline constexpr double kFrameDueSlackS = 1e-7;

/// A stream's end of a scene: receives every step's snapshot. Only the
/// scene's FrameFanOut calls it, holding no lock of the runner's
/// (server/lock_order.h); it must not call back into the SceneRunner, its
/// StreamRegistry or its FrameFanOut (SceneRunner aborts when it does): a
/// stream that must end ends its own writes, and detaches when its RPC is
/// done.
class FrameSink {
 public:
  virtual ~FrameSink() = default;
  /// Called on the scene's frames thread after each step, in step order;
  /// must not block.
  virtual void Offer(std::shared_ptr<const StepSnapshot> snapshot) = 0;
  /// The scene time (StepSnapshot::time_s) of the first step whose Offer
  /// the stream takes (within kFrameDueSlackS); 0 for every step. Called
  /// on the frames thread after an Offer: the frames thread is not woken
  /// for steps before the earliest of its streams' (FrameFanOut).
  virtual double NextDueS() const { return 0; }
  /// The stream is ended (the scene deleted or shutting down, its tool
  /// taken over, its device silent): send what is pending, then end the
  /// stream with `status`. Called at most once; no Offer after.
  virtual void Close(const absl::Status& status) = 0;
};

}  // namespace hs

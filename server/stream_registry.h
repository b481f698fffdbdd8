#pragma once
// The streams attached to one scene: devices (each holding one tool),
// viewers, what each needs the scene to compute, and the devices' latest
// poses. Thread-safe: gRPC threads attach, detach and send poses; the
// stepping thread takes the fresh poses; the frames thread lists the
// streams.

#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "common/core/types.h"
#include "common/sim/effects.h"
#include "server/priority_inheriting_mutex.h"
#include "server/step_snapshot.h"

namespace hs {

/// A device pose waiting for the next step.
struct PendingPose {
  Isometry3d X_WD = Isometry3d::Identity();
  AppliedPose stamp;
  bool fresh = false;
  /// The first pose of the device that holds the tool now (Scene::SeatDevice).
  bool seat = false;
};

/// The device poses one step takes: (tool, pose) entries [0, count); the
/// entries past them keep their storage (tool names included) for later
/// steps, so that taking poses allocates nothing once warm.
struct FreshPoses {
  std::vector<std::pair<std::string, PendingPose>> entries;
  size_t count = 0;
  /// Who held each tool then; a new map after every change, so a step
  /// keeps the one it took without copying.
  std::shared_ptr<const ToolHolders> holders;
  std::span<const std::pair<std::string, PendingPose>> taken() const {
    return {entries.data(), count};
  }
};

/// A device's ask when it attaches.
struct DeviceClaim {
  /// The tool it drives.
  std::string tool;
  /// What the scene must compute for it (with prerequisites).
  EffectSet needs;
  /// Who holds the tool as frames name it (Caller::name), "" for none.
  std::string holder{};
};

class StreamRegistry {
 public:
  /// `devices_fresh` is told, with the registry's lock held (so nothing
  /// can slip between), whether every attached device has sent a pose the
  /// last TakeFreshPoses did not take: true after a pose or a detach that
  /// makes it so, false after TakeFreshPoses.
  explicit StreamRegistry(std::function<void(bool)> devices_fresh)
      : devices_fresh_(std::move(devices_fresh)) {}

  /// Lets `sink` drive the claimed tool. `has_tool` is asked under the lock. NOT_FOUND when it says
  /// no, FAILED_PRECONDITION when another device holds the tool, UNAVAILABLE once closed. With
  /// `take_over`, a device holding the tool is ended with that status (FrameSink::Close) and
  /// forgotten instead, its pose not taken yet dropped, and `*displaced` set.
  absl::Status AttachDevice(FrameSink* sink, const DeviceClaim& claim,
                            const std::function<bool(const std::string&)>& has_tool,
                            const absl::Status* take_over = nullptr, bool* displaced = nullptr);
  /// Lets `sink` receive frames. UNAVAILABLE once closed.
  absl::Status AttachViewer(FrameSink* sink, EffectSet needs);
  /// Forgets `sink` and frees its tool. Returns its tool ("" for a
  /// viewer), none when it was not attached.
  std::optional<std::string> Detach(FrameSink* sink);

  /// The pose of `sink`'s tool for the next step (latest wins); ignored
  /// for a viewer or a stream not attached. A device's first pose seats it
  /// (PendingPose::seat), until a step takes it.
  void SetPose(FrameSink* sink, const Isometry3d& X_WD, const AppliedPose& stamp);
  /// Ends (FrameSink::Close with `status`) and forgets every device not
  /// heard from (attached or sent a pose) since `silent_since`, as a
  /// take-over does; appends their tools to `released`.
  void EndSilentDevices(std::chrono::steady_clock::time_point silent_since,
                        const absl::Status& status, std::vector<std::string>& released);
  /// Moves the poses not taken before into `fresh`, with who holds each
  /// tool, and returns what the streams need, at one instant.
  EffectSet TakeFreshPoses(FreshPoses& fresh);

  /// The attached streams, into `out` (cleared first).
  void ListSinks(std::vector<FrameSink*>& out) const;
  /// FAILED_PRECONDITION naming a tool a device holds that `has_tool`
  /// says is gone; checked under the lock, so no device attaches meanwhile
  /// when `then` (run under it on OK) swaps the scene.
  absl::Status WhileToolsHeld(const std::function<bool(const std::string&)>& has_tool,
                              const std::function<void()>& then);
  /// Ends every stream with `status` (FrameSink::Close); later attaches
  /// are UNAVAILABLE.
  void CloseAll(const absl::Status& status);

  /// Devices and viewers attached, and the tools the devices hold; and
  /// how many of each ever attached (one that came and went between two
  /// looks still counts).
  struct Counts {
    int devices = 0;
    int viewers = 0;
    std::vector<std::string> claimed_tools;
    int64_t devices_joined = 0;
    int64_t viewers_joined = 0;
  };
  Counts counts() const;

 private:
  struct Attached {
    std::string tool{};  // empty for viewers
    EffectSet needs;
    std::string holder{};
    bool sent_pose = false;
    std::chrono::steady_clock::time_point heard{};  // attached or sent its last pose
  };
  // Whether every attached device has a pose not taken yet (and there is one).
  bool DevicesFreshLocked() const;
  // Forgets device `it`, ending it with `status`, its pose not taken yet dropped.
  void EndDeviceLocked(std::map<FrameSink*, Attached>::iterator it, const absl::Status& status);
  // Makes holders_ anew from sinks_.
  void UpdateHoldersLocked();

  const std::function<void(bool)> devices_fresh_;
  mutable PriorityInheritingMutex mu_;
  std::map<FrameSink*, Attached> sinks_;
  std::map<std::string, PendingPose> pending_;  // by tool name
  std::shared_ptr<const ToolHolders> holders_ = std::make_shared<const ToolHolders>();
  bool closed_ = false;
  int64_t devices_joined_ = 0;
  int64_t viewers_joined_ = 0;
};

}  // namespace hs

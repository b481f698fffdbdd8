#pragma once
// The streams attached to one scene: devices (each holding one tool),
// viewers, what each needs the scene to compute, and the devices' latest
// poses. Thread-safe: gRPC threads attach, detach and send poses; the
// stepping thread takes the fresh poses; the frames thread lists the
// streams and takes the ends to hand to them. It calls no stream and no
// other class while it holds its lock: a stream it ends waits in the list
// TakeEnds returns, for the frames thread to tell (server/lock_order.h).
//
// Tools are named once, when a device attaches; from then on poses and
// holders are kept by the tool's ObjectId in the scene running now, which
// RemapTools follows when the scene is replaced.

#include <atomic>
#include <chrono>
#include <cstdint>
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

/// A scene's tools as devices name them.
struct SceneTools {
  /// (name, ObjectId) of each tool.
  std::vector<std::pair<std::string, ObjectId>> tools;
  /// Objects in the scene: every ObjectId is below it.
  size_t object_count = 0;
  /// The tool called `name`, -1 when there is none.
  ObjectId Find(const std::string& name) const;
};

/// A device pose waiting for the next step.
struct PendingPose {
  Isometry3d X_WD = Isometry3d::Identity();
  AppliedPose stamp;
  bool fresh = false;
  /// The first pose of the device that holds the tool now (Scene::SeatDevice).
  bool seat = false;
  /// What the device asked of its local model: a fresh one with this pose
  /// or one it replaced; the radius of the latest.
  LocalModelRequest model;
};

/// The device poses one step takes: (tool, pose) entries [0, count), in
/// ObjectId order; storage is kept for later steps, so that taking poses
/// allocates nothing once warm.
struct FreshPoses {
  std::vector<std::pair<ObjectId, PendingPose>> entries;
  size_t count = 0;
  /// Who held each tool then; a new table after every change, so a step
  /// keeps the one it took without copying.
  std::shared_ptr<const ToolHolders> holders;
  /// How many takes the registry has made, this one included.
  uint64_t generation = 0;
  std::span<const std::pair<ObjectId, PendingPose>> taken() const {
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

/// A stream to end, and how (FrameSink::Close).
struct SinkEnd {
  FrameSink* sink = nullptr;
  absl::Status status;
};

/// What Detach and SetPose tell the runner.
struct StreamChange {
  /// The detached stream's tool ("" for a viewer); none when the stream was
  /// not attached. Detach only.
  std::optional<std::string> tool;
  /// Set when every attached device now has a pose the last take did not
  /// take: the generation of that take (FreshPoses::generation).
  std::optional<uint64_t> devices_fresh_since;
};

class StreamRegistry {
 public:
  /// The scene's tools, which devices may claim.
  explicit StreamRegistry(SceneTools tools);

  /// Lets `sink` drive the claimed tool. NOT_FOUND when the scene has no
  /// such tool, FAILED_PRECONDITION when another device holds it,
  /// UNAVAILABLE once closed. With `take_over`, a device holding the tool
  /// is forgotten instead, its pose not taken yet dropped, and queued to be
  /// ended with that status (TakeEnds); `*displaced` is set.
  absl::Status AttachDevice(FrameSink* sink, const DeviceClaim& claim,
                            const absl::Status* take_over = nullptr, bool* displaced = nullptr);
  /// Lets `sink` receive frames. UNAVAILABLE once closed.
  absl::Status AttachViewer(FrameSink* sink, EffectSet needs);
  /// Forgets `sink`, frees its tool, and drops an end queued for it.
  StreamChange Detach(FrameSink* sink);

  /// The pose of `sink`'s tool for the next step (latest wins); ignored
  /// for a viewer or a stream not attached. A device's first pose seats it
  /// (PendingPose::seat), until a step takes it; so does a request for a
  /// fresh model (`model.stale`).
  StreamChange SetPose(FrameSink* sink, const Isometry3d& X_WD, const AppliedPose& stamp,
                       const LocalModelRequest& model = {});
  /// Forgets every device not heard from (attached or sent a pose) since
  /// `silent_since`, queuing its end with `status` as a take-over does;
  /// appends their tools to `released`. Returns what SetPose would, as the
  /// devices left may all have sent.
  StreamChange EndSilentDevices(std::chrono::steady_clock::time_point silent_since,
                                const absl::Status& status, std::vector<std::string>& released);
  /// Moves the poses not taken before into `fresh`, with who holds each
  /// tool, and returns what the streams need, at one instant.
  EffectSet TakeFreshPoses(FreshPoses& fresh);

  /// The attached streams, into `out` (cleared first).
  void ListSinks(std::vector<FrameSink*>& out) const;
  /// Counts the streams attached and the ends queued, ever: the same
  /// count as before means no stream came and no new end waits.
  uint64_t changes() const { return changes_.load(std::memory_order_acquire); }
  /// Moves the ends queued (take-overs, silent devices, CloseAll) into
  /// `out` (cleared first), for the caller to hand to their streams.
  void TakeEnds(std::vector<SinkEnd>& out);
  /// Takes the tools of the scene that replaces this one: the held tools
  /// and their poses move to their ids in `next`. FAILED_PRECONDITION
  /// naming a held tool that `next` lacks, and no change.
  absl::Status RemapTools(SceneTools next);
  /// Queues the end of every stream with `status`; later attaches are
  /// UNAVAILABLE. The streams stay attached until they detach.
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
    ObjectId tool = -1;  // -1 for viewers
    EffectSet needs;
    std::string holder{};
    bool sent_pose = false;
    std::chrono::steady_clock::time_point heard{};  // attached or sent its last pose
  };
  using SinkMap = std::map<FrameSink*, Attached>;
  // The tool's name in the scene running now.
  const std::string& ToolName(ObjectId tool) const;
  // Set when every attached device has a pose not taken yet (and there is one).
  std::optional<uint64_t> DevicesFreshLocked() const;
  // Forgets device `it`, queuing its end with `status`; its pose not taken yet dropped.
  void EndDeviceLocked(SinkMap::iterator it, const absl::Status& status);
  // Forgets the pose of `tool` not taken yet.
  void DropPendingLocked(ObjectId tool);
  // Makes holders_ anew from sinks_.
  void UpdateHoldersLocked();

  mutable PriorityInheritingMutex mu_{LockLevel::kStreams};
  SceneTools tools_;
  SinkMap sinks_;
  std::vector<PendingPose> pending_;  // by ObjectId
  int devices_ = 0;
  int devices_with_fresh_pose_ = 0;
  uint64_t takes_ = 0;
  std::shared_ptr<const ToolHolders> holders_;
  std::vector<SinkEnd> ends_;
  bool closed_ = false;
  int64_t devices_joined_ = 0;
  int64_t viewers_joined_ = 0;
  std::atomic<uint64_t> changes_{0};  // written under mu_
};

}  // namespace hs

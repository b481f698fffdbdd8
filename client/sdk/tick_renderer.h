#pragma once
// The device's side of a Device: each tick, the force of the newest local
// model the network thread handed over (a HapticLoop), zero force while
// the stream is down or has brought no model yet. A new stream starts a
// new loop (the device is seated again). Without the local model
// (DeviceOptions::local_model false) it returns the newest frame's force. Wait-free: no lock, no
// allocation after construction (the loop's model buffers are grown to the server's 16 planes at
// construction, its surface's to the largest surface, about 1.8 MB, and a new loop is copied over
// the old one, which keeps them), no free (the network thread holds the surfaces the loop drops),
// no system call.

#include <cstdint>

#include "client/haptic_loop/haptic_loop.h"
#include "client/sdk/device_feed.h"
#include "haptics/device.h"
#include "haptics/pose.h"

namespace hs::sdk {

/// What the loop counted since the renderer was made, over every stream.
struct LoopCounts {
  int64_t beyond_validity_ticks = 0;
  int64_t rejected_poses = 0;
  int64_t models_rejected = 0;
  int64_t models_restarted = 0;
  int64_t passivity_ticks = 0;
  double passivity_dissipated_j = 0;
};

class TickRenderer {
 public:
  /// Uses options.tick_s, local_model and max_passivity_damping_ns_per_m.
  explicit TickRenderer(const haptics::DeviceOptions& options);

  /// One tick with the device at `pose` and `feed` the newest state of the
  /// stream. A pose with a non-finite number or a quaternion that is not
  /// unit within 1e-6 returns the last output with kInvalidPose.
  haptics::TickOutput Tick(const haptics::Pose& pose, const Feed& feed);

  /// Whether `pose` may be rendered and sent.
  static bool ValidPose(const haptics::Pose& pose);

  int64_t beyond_validity_ticks() const { return beyond_validity_ticks_; }
  LoopCounts counts() const;

 private:
  // The local model's tick, the device at `X_WD`.
  haptics::TickOutput RenderModel(const haptics::Pose& pose);
  // Starts the loop afresh for a new stream, keeping its counts.
  void Reseat();

  const bool local_model_;
  // A loop that has not ticked: copied over loop_ for each new stream.
  const HapticLoop fresh_;
  HapticLoop loop_;
  int64_t beyond_validity_ticks_ = 0;
  uint64_t stream_ = 0;
  uint64_t model_serial_ = 0;
  bool has_model_ = false;
  haptics::TickOutput last_;
  int64_t rejected_poses_ = 0;
  // The counts as a new stream began (the loop's since are added to them).
  LoopCounts earlier_;
};

}  // namespace hs::sdk

#pragma once
// One closed-loop run of a remote device: a simulated hand
// (hand_operator.h) holds the device, which ticks at 1 kHz and renders
// what the SDK's Device renders (with the local model, from its newest
// model; without, the server's force as it arrives). The run moves the
// hand under the force, and measures what the hand felt and how deep the
// device went. The device is the caller's: `hapticctl drive --operator`
// ticks a haptics::Device over gRPC (remote_drive.h), the in-process tests
// the same device's parts on a simulated clock.

#include <cstdint>
#include <mutex>
#include <span>
#include <string>
#include <vector>

#include "client/remote/hand_operator.h"
#include "client/remote/shaped_stream.h"
#include "client/sdk/device_config.h"
#include "client/sdk/tick_renderer.h"
#include "common/core/types.h"
#include "haptics/device.h"
#include "haptics/pose.h"
#include "haptics/v1/session_service.pb.h"

namespace hs::cli {

/// How deep the device at `p_WD` is in the objects whose contacts have the
/// unit normals `normals_W` (each from the object toward the tool), while
/// the proxy rests at `p_WP` on their surface: the device's distance behind
/// the proxy along each normal, the deepest (0 in front of them all). It is
/// the hand's depth under the surface it touches, whatever the path: the
/// contact's own depth is measured along the tool's motion since the last
/// applied pose, which, when a stalled link hands the server poses in a
/// burst, runs sideways through the object and reads deeper than the hand
/// is.
double DepthBehindProxy(const Vector3d& p_WD, const Vector3d& p_WP,
                        std::span<const Vector3d> normals_W);

/// DepthBehindProxy of a tool's state in a frame: its device and proxy
/// poses and its contacts' normals (0 when one is not finite).
double FrameDepth(const haptics::v1::ToolState& tool);

struct RemoteRunOptions {
  OperatorMotion motion = OperatorMotion::kPress;
  HandParams hand;
  /// Render from the local model on the device; else apply the server's force.
  bool local_model = true;
  LinkConditions link;
  double tick_s = 1e-3;
  /// Poses sent a second (the SDK Device's rate_hz); the device's loop
  /// renders every tick all the same.
  double pose_rate_hz = 250;
  /// The device loop's passivity controller (DeviceOptions).
  double max_passivity_damping_ns_per_m = 30;

  /// The Device's options for the run.
  haptics::DeviceOptions Device() const;
};

/// What a run measured.
struct RemoteSummary {
  int64_t ticks = 0;
  /// Work done on the hand by the rendered force, joules: positive means
  /// the rendering put energy into the hand.
  double energy_j = 0;
  /// The largest change of the rendered force between two ticks, newtons.
  double max_force_step_n = 0;
  /// How far the device went into the objects (DepthBehindProxy at each
  /// applied pose, as the server's frame gives it), p99 and largest, metres.
  double penetration_p99_m = 0;
  double penetration_max_m = 0;
  /// RMS of the rendered force against a reference run's, tick by tick, N
  /// (0 without a reference), and the RMS of the reference's force.
  double force_rms_error_n = 0;
  double reference_force_rms_n = 0;
  double max_force_n = 0;
  /// The one-way hold the link applied on average, each way, milliseconds,
  /// and the round trip seen: from sending a pose to reading the frame
  /// that applied it, p50 and p99.
  double uplink_mean_ms = 0;
  double downlink_mean_ms = 0;
  double round_trip_p50_ms = 0;
  double round_trip_p99_ms = 0;
  int64_t poses_lost = 0;
  int64_t frames_lost = 0;
  /// Messages the link stalled (and the ones behind them with them).
  int64_t poses_stalled = 0;
  int64_t frames_stalled = 0;
  int64_t models_rejected = 0;
  /// Models whose device pose the loop no longer held (the proxy restarted
  /// at the server's).
  int64_t models_restarted = 0;
  int64_t beyond_validity_ticks = 0;
  /// Ticks the loop's passivity controller damped, and the work it took
  /// back from the hand, joules (haptic_loop.h).
  int64_t passivity_ticks = 0;
  double passivity_dissipated_j = 0;
};

/// How long a run waits for its device to be live before the hand moves,
/// seconds: a run of N ticks ends after N ticks of motion or this long.
inline constexpr double kLongestWaitForDeviceS = 10;

class RemoteRun {
 public:
  /// The hand starts at rest at `start`, the device's pose (world frame).
  RemoteRun(const RemoteRunOptions& options, const Isometry3d& start);

  /// Where the hand holds the device now.
  haptics::Pose DevicePose() const;
  /// The device rendered `out` at `now_s` (seconds on the ticks' clock)
  /// for DevicePose. The hand holds still until the device is live (its
  /// first model, or without the local model its first frame), as an
  /// operator waits for the device to say so; then it feels the force and
  /// moves under it.
  void Feel(double now_s, const haptics::TickOutput& out);
  /// Ticks the hand has moved through (those after the device was live).
  int64_t ticks_rendered() const { return static_cast<int64_t>(forces_.size()); }

  /// The device read `frame` (sdk::DeviceConfig::on_frame): when it
  /// applied one of the device's poses, the round trip and how deep the
  /// device on `tool` was there (FrameDepth). The first frame of each pose
  /// counts. Any thread.
  void Read(const haptics::v1::Frame& frame, const sdk::FrameRead& read, const std::string& tool);

  /// The rendered force of each tick since the device was live, world
  /// frame, N.
  const std::vector<Vector3d>& forces() const { return forces_; }
  /// The device position at each of those ticks, world frame, metres.
  const std::vector<Vector3d>& device_positions() const { return positions_; }
  /// The measures; `reference`: the forces of the zero-latency run of the
  /// same operator, for force_rms_error_n (empty: 0); `device` what the
  /// device's loop counted, `link` what the link did.
  RemoteSummary Summary(std::span<const Vector3d> reference, const sdk::LoopCounts& device,
                        const LinkStats& link) const;

 private:
  RemoteRunOptions options_;
  HandOperator hand_;
  // When the device was first live, seconds on the ticks' clock (-1: not yet).
  double engaged_at_s_ = -1;
  std::vector<Vector3d> forces_;
  std::vector<Vector3d> positions_;
  // What the frames said, by the thread that reads them.
  mutable std::mutex applied_mutex_;
  uint64_t newest_applied_ = 0;
  // At each pose applied.
  std::vector<double> depths_m_;
  std::vector<double> round_trips_ms_;
};

}  // namespace hs::cli

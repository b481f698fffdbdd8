#pragma once
// One closed-loop run of a remote device: a simulated hand (hand_operator.h)
// holds the device, which ticks at 1 kHz and talks to the server through a
// simulated link (delay_line.h) both ways. With the local model on, the
// device renders from the latest local contact model itself
// (client/haptic_loop); off, it applies the server's forces as they
// arrive. The run measures what the hand felt. The transport is the
// caller's: it delivers the poses due to the server and hands back the
// frames the server sends (`hapticctl drive` over gRPC, tests in process).

#include <atomic>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

#include "client/haptic_loop/haptic_loop.h"
#include "client/haptic_loop/model_request.h"
#include "client/remote/delay_line.h"
#include "client/remote/hand_operator.h"

namespace hs::cli {

/// A pose on its way to the server.
struct PoseMessage {
  uint64_t sequence = 0;
  Isometry3d X_WD = Isometry3d::Identity();
  /// With the local model: the device went past its model's validity
  /// sphere since the last pose (ToolPose.model_stale), and the validity
  /// radius it wants (ToolPose.validity_radius_m; 0: the scene's).
  bool model_stale = false;
  double validity_radius_m = 0;
};

/// What the device reads from a frame of its tool.
struct ServerFrame {
  /// The sequence of the last pose the step applied (0 before the first).
  uint64_t applied_sequence = 0;
  Vector3d force_W = Vector3d::Zero();
  /// The frame's local contact model, when it carried a valid one.
  std::optional<LocalModel> model;
  /// It carried one that failed the checks (not rendered).
  bool model_rejected = false;
  /// How deep the device is in the objects at the applied pose, metres
  /// (DepthBehindProxy).
  double depth_m = 0;
};

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

struct RemoteRunOptions {
  OperatorMotion motion = OperatorMotion::kPress;
  HandParams hand;
  /// Render from the local model on the device; else apply the server's force.
  bool local_model = true;
  LinkConditions link;
  double tick_s = 1e-3;
  /// Poses sent a second: the newest pose every 1 / pose_rate_hz, as the
  /// SDK's Device sends them (its default rate); the device's loop renders
  /// every tick all the same. At or above 1 / tick_s, one a tick.
  double pose_rate_hz = 250;
  HapticLoopOptions loop;
  /// With the local model: ask for a validity radius sized from the round
  /// trip and the hand's speed (validity_sizer.h); false keeps the scene's.
  bool size_validity = true;
  ValiditySizerOptions sizer;
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

  /// Tick `k`, at k * tick_s: reads the frames the link delivers by then,
  /// renders the force, moves the hand under it and, on the ticks of the
  /// pose rate, sends the device's pose (sequence k + 1). The hand holds
  /// still until the device is live (its first model, or with the local
  /// model off its first frame), as an operator waits for the device to
  /// say so; its motion starts then.
  void Tick(int64_t k);
  /// Ticks the hand has moved through (those after the device was live).
  int64_t ticks_rendered() const { return static_cast<int64_t>(forces_.size()); }
  /// Calls `send(PoseMessage)` for each pose that reaches the server by
  /// `now_s` (seconds on the ticks' clock), in order.
  template <typename F>
  void DeliverPoses(double now_s, F&& send) {
    up_.PopDue(now_s, send);
  }
  /// A frame the server sent at `now_s`, onto the link back.
  void FromServer(double now_s, ServerFrame frame);

  /// The rendered force of each tick since the device was live, world
  /// frame, N.
  const std::vector<Vector3d>& forces() const { return forces_; }
  /// The device position at each of those ticks, world frame, metres.
  const std::vector<Vector3d>& device_positions() const { return positions_; }
  /// The measures; `reference`: the forces of the zero-latency run of the
  /// same operator, for force_rms_error_n (empty: 0).
  RemoteSummary Summary(std::span<const Vector3d> reference) const;

 private:
  void Read(const ServerFrame& frame, int64_t tick);

  RemoteRunOptions options_;
  HandOperator hand_;
  HapticLoop loop_;
  ModelRequester model_requester_;
  // A pose goes every this many ticks (pose_rate_hz).
  int64_t pose_period_ticks_ = 1;
  DelayLine<PoseMessage> up_;
  DelayLine<ServerFrame> down_;
  Vector3d server_force_ = Vector3d::Zero();
  bool has_frame_ = false;
  // When the device was first live, seconds on the ticks' clock (-1: not yet).
  double engaged_at_s_ = -1;
  uint64_t newest_applied_ = 0;
  // Poses sent so far: a frame that reports a later one applied is not
  // this run's (the tool's last device before it), and is not read.
  std::atomic<uint64_t> sent_{0};
  std::vector<Vector3d> forces_;
  std::vector<Vector3d> positions_;
  // Depth at each applied pose (by sequence), recorded as the server sent it.
  std::unordered_map<uint64_t, double> depth_by_sequence_;
  std::vector<double> round_trips_ms_;
  int64_t models_rejected_ = 0;
};

}  // namespace hs::cli

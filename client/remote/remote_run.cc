#include "client/remote/remote_run.h"

#include <algorithm>
#include <cmath>

#include "client/percentiles.h"
#include "common/api/proto_convert.h"

namespace hs::cli {

namespace pb = haptics::v1;

double DepthBehindProxy(const Vector3d& p_WD, const Vector3d& p_WP,
                        std::span<const Vector3d> normals_W) {
  double depth = 0;
  for (const Vector3d& n : normals_W) depth = std::max(depth, (p_WP - p_WD).dot(n));
  return depth;
}

double FrameDepth(const pb::ToolState& tool) {
  const absl::StatusOr<Vector3d> p_WD = VectorFromProto(tool.device_pose().position_m(), "device");
  const absl::StatusOr<Vector3d> p_WP = VectorFromProto(tool.proxy_pose().position_m(), "proxy");
  std::vector<Vector3d> normals;
  for (const pb::Contact& c : tool.contacts()) {
    const absl::StatusOr<Vector3d> n = VectorFromProto(c.normal_w(), "normal");
    if (n.ok()) normals.push_back(*n);
  }
  return p_WD.ok() && p_WP.ok() ? DepthBehindProxy(*p_WD, *p_WP, normals) : 0;
}

haptics::DeviceOptions RemoteRunOptions::Device() const {
  return {.rate_hz = pose_rate_hz,
          .local_model = local_model,
          .max_passivity_damping_ns_per_m = max_passivity_damping_ns_per_m,
          .tick_s = tick_s};
}

RemoteRun::RemoteRun(const RemoteRunOptions& options, const Isometry3d& start)
    : options_(options), hand_(options.motion, options.hand, start) {}

haptics::Pose RemoteRun::DevicePose() const {
  const Isometry3d X_WD = hand_.DevicePose();
  const Eigen::Quaterniond q(X_WD.linear());
  haptics::Pose pose;
  for (int i = 0; i < 3; ++i) pose.position_m[i] = X_WD.translation()[i];
  pose.orientation_wxyz[0] = q.w();
  pose.orientation_wxyz[1] = q.x();
  pose.orientation_wxyz[2] = q.y();
  pose.orientation_wxyz[3] = q.z();
  return pose;
}

void RemoteRun::Feel(double now_s, const haptics::TickOutput& out) {
  const uint32_t live = options_.local_model ? haptics::kHasModel : haptics::kConnected;
  if (engaged_at_s_ < 0 && (out.flags & live) != 0) engaged_at_s_ = now_s;
  // The hand waits, at rest, for the device to be live.
  if (engaged_at_s_ < 0) return;
  const Vector3d force(out.force_n[0], out.force_n[1], out.force_n[2]);
  forces_.push_back(force);
  positions_.push_back(hand_.DevicePose().translation());
  hand_.Step(now_s - engaged_at_s_, options_.tick_s, force);
}

void RemoteRun::Read(const pb::Frame& frame, const sdk::FrameRead& read, const std::string& tool) {
  if (read.applied_sequence == 0) return;
  std::lock_guard lock(applied_mutex_);
  if (read.applied_sequence <= newest_applied_) return;  // read already
  for (const pb::ToolState& state : frame.tools()) {
    if (state.tool() != tool) continue;
    newest_applied_ = read.applied_sequence;
    round_trips_ms_.push_back(static_cast<double>(read.round_trip_ns) * 1e-6);
    depths_m_.push_back(FrameDepth(state));
  }
}

RemoteSummary RemoteRun::Summary(std::span<const Vector3d> reference, const sdk::LoopCounts& device,
                                 const LinkStats& link) const {
  RemoteSummary s;
  s.ticks = static_cast<int64_t>(forces_.size());
  s.energy_j = hand_.work_j();
  double error_sq = 0;
  double reference_sq = 0;
  for (size_t i = 0; i < forces_.size(); ++i) {
    s.max_force_n = std::max(s.max_force_n, forces_[i].norm());
    if (i > 0)
      s.max_force_step_n = std::max(s.max_force_step_n, (forces_[i] - forces_[i - 1]).norm());
    const Vector3d ref = i < reference.size() ? reference[i] : Vector3d::Zero();
    error_sq += (forces_[i] - ref).squaredNorm();
    reference_sq += ref.squaredNorm();
  }
  if (!reference.empty() && !forces_.empty()) {
    s.force_rms_error_n = std::sqrt(error_sq / static_cast<double>(forces_.size()));
    s.reference_force_rms_n = std::sqrt(reference_sq / static_cast<double>(forces_.size()));
  }
  {
    std::lock_guard lock(applied_mutex_);
    std::vector<double> depths = depths_m_;
    const Percentiles depth = Summarize(depths);
    s.penetration_p99_m = depth.p99;
    s.penetration_max_m = depth.max;
    std::vector<double> trips = round_trips_ms_;
    const Percentiles trip = Summarize(trips);
    s.round_trip_p50_ms = trip.p50;
    s.round_trip_p99_ms = trip.p99;
  }
  s.uplink_mean_ms = link.uplink_mean_ms;
  s.downlink_mean_ms = link.downlink_mean_ms;
  s.poses_lost = link.poses_lost;
  s.frames_lost = link.frames_lost;
  s.poses_stalled = link.poses_stalled;
  s.frames_stalled = link.frames_stalled;
  s.models_rejected = device.models_rejected;
  s.models_restarted = device.models_restarted;
  s.beyond_validity_ticks = device.beyond_validity_ticks;
  s.passivity_ticks = device.passivity_ticks;
  s.passivity_dissipated_j = device.passivity_dissipated_j;
  return s;
}

}  // namespace hs::cli

#include "client/remote/remote_run.h"

#include <algorithm>
#include <cmath>

#include "client/percentiles.h"

namespace hs::cli {

double DepthBehindProxy(const Vector3d& p_WD, const Vector3d& p_WP,
                        std::span<const Vector3d> normals_W) {
  double depth = 0;
  for (const Vector3d& n : normals_W) depth = std::max(depth, (p_WP - p_WD).dot(n));
  return depth;
}

RemoteRun::RemoteRun(const RemoteRunOptions& options, const Isometry3d& start)
    : options_(options),
      hand_(options.motion, options.hand, start),
      loop_(options.loop),
      model_requester_(options.sizer),
      up_(options.link, 0),
      down_(options.link, 1) {
  if (options.pose_rate_hz > 0 && options.pose_rate_hz * options.tick_s < 1) {
    pose_period_ticks_ = std::llround(1 / (options.pose_rate_hz * options.tick_s));
  }
}

void RemoteRun::Read(const ServerFrame& frame, int64_t tick) {
  if (frame.model_rejected) ++models_rejected_;
  if (frame.applied_sequence > sent_) return;  // not this run's
  // A model serves whichever of this run's poses the frame applied (none
  // yet included): the server sends each revision once, and holds it
  // while it serves.
  if (frame.model && !loop_.SetModel(*frame.model)) ++models_rejected_;
  if (frame.applied_sequence <= newest_applied_) return;  // an older pose's
  newest_applied_ = frame.applied_sequence;
  // Pose n went out at tick n - 1.
  round_trips_ms_.push_back(
      static_cast<double>(tick - static_cast<int64_t>(frame.applied_sequence) + 1) *
      options_.tick_s * 1e3);
  model_requester_.AddRoundTrip(static_cast<double>(tick) * options_.tick_s,
                                round_trips_ms_.back() * 1e-3);
  server_force_ = frame.force_W;
  has_frame_ = true;
}

void RemoteRun::Tick(int64_t k) {
  const double now_s = static_cast<double>(k) * options_.tick_s;
  down_.PopDue(now_s, [&](const ServerFrame& frame) { Read(frame, k); });
  const Isometry3d X_WD = hand_.DevicePose();
  const Vector3d rendered = options_.local_model ? loop_.Tick(X_WD).force_W : server_force_;
  if (engaged_at_s_ < 0 && (options_.local_model ? loop_.has_model() : has_frame_)) {
    engaged_at_s_ = now_s;
  }
  // The hand waits, at rest, for the device to be live.
  if (engaged_at_s_ >= 0) {
    forces_.push_back(rendered);
    positions_.push_back(X_WD.translation());
    hand_.Step(now_s - engaged_at_s_, options_.tick_s, rendered);
  }
  if (k % pose_period_ticks_ != 0) return;
  PoseMessage pose{.sequence = static_cast<uint64_t>(k) + 1, .X_WD = hand_.DevicePose()};
  if (options_.local_model) {
    const ModelRequest request = model_requester_.ForPose(
        now_s + options_.tick_s, pose.X_WD.translation(), loop_.beyond_validity_ticks());
    pose.model_stale = request.model_stale;
    if (options_.size_validity) pose.validity_radius_m = request.validity_radius_m;
  }
  up_.Push(now_s, pose);
  sent_ = static_cast<uint64_t>(k) + 1;
}

void RemoteRun::FromServer(double now_s, ServerFrame frame) {
  if (frame.applied_sequence > 0 && frame.applied_sequence <= sent_) {
    depth_by_sequence_.try_emplace(frame.applied_sequence, frame.depth_m);
  }
  down_.Push(now_s, std::move(frame));
}

RemoteSummary RemoteRun::Summary(std::span<const Vector3d> reference) const {
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
  std::vector<double> depths;
  depths.reserve(depth_by_sequence_.size());
  for (const auto& [sequence, depth] : depth_by_sequence_) depths.push_back(depth);
  const Percentiles depth = Summarize(depths);
  s.penetration_p99_m = depth.p99;
  s.penetration_max_m = depth.max;
  std::vector<double> trips = round_trips_ms_;
  const Percentiles trip = Summarize(trips);
  s.round_trip_p50_ms = trip.p50;
  s.round_trip_p99_ms = trip.p99;
  s.uplink_mean_ms = up_.mean_delay_s() * 1e3;
  s.downlink_mean_ms = down_.mean_delay_s() * 1e3;
  s.poses_lost = up_.lost();
  s.frames_lost = down_.lost();
  s.poses_stalled = up_.stalled();
  s.frames_stalled = down_.stalled();
  s.models_rejected = models_rejected_;
  s.models_restarted = loop_.restarted_models();
  s.beyond_validity_ticks = loop_.beyond_validity_ticks();
  s.passivity_ticks = loop_.passivity_ticks();
  s.passivity_dissipated_j = loop_.passivity_dissipated_j();
  return s;
}

}  // namespace hs::cli

#include "client/sdk/tick_renderer.h"

#include <cmath>

namespace hs::sdk {
namespace {

// The most planes a server's model holds (docs/remote-haptics.md).
constexpr int kMaxPlanes = 16;

// A valid model of kMaxPlanes planes: taking it twice grows both of a
// loop's model buffers (it swaps them) to their largest.
LocalModel WarmUpModel() {
  LocalModel model;
  model.validity_radius_m = 1e-3;
  model.force_clamp_n = 1;
  ConstraintPlane plane;
  plane.stiffness_n_per_m = 1;
  model.planes.assign(kMaxPlanes, plane);
  return model;
}

haptics::TickOutput Zero(uint32_t flags) {
  haptics::TickOutput out;
  out.flags = flags;
  return out;
}

}  // namespace

TickRenderer::TickRenderer(const haptics::DeviceOptions& options)
    : local_model_(options.local_model),
      fresh_(HapticLoopOptions{
          .tick_s = options.tick_s,
          .max_passivity_damping_ns_per_m = options.max_passivity_damping_ns_per_m}),
      loop_(fresh_) {
  const LocalModel warm = WarmUpModel();
  for (int i = 0; i < 2; ++i) {
    loop_.SetModel(warm);
    loop_.Tick(warm.X_WP);
  }
  // Copying keeps the grown buffers: the vectors' storage is reused.
  loop_ = fresh_;
}

bool TickRenderer::ValidPose(const haptics::Pose& pose) {
  double norm2 = 0;
  for (double q : pose.orientation_wxyz) {
    if (!std::isfinite(q)) return false;
    norm2 += q * q;
  }
  for (double p : pose.position_m) {
    if (!std::isfinite(p)) return false;
  }
  return std::abs(std::sqrt(norm2) - 1) <= 1e-6;
}

LoopCounts TickRenderer::counts() const {
  LoopCounts c = earlier_;
  c.beyond_validity_ticks = beyond_validity_ticks_;
  c.rejected_poses = rejected_poses_;
  c.models_rejected += loop_.rejected_models();
  c.models_restarted += loop_.restarted_models();
  c.passivity_ticks += loop_.passivity_ticks();
  c.passivity_dissipated_j += loop_.passivity_dissipated_j();
  return c;
}

void TickRenderer::Reseat() {
  earlier_ = counts();  // counts() takes its own two counts from the renderer
  loop_ = fresh_;
}

haptics::TickOutput TickRenderer::Tick(const haptics::Pose& pose, const Feed& feed) {
  if (!ValidPose(pose)) {
    ++rejected_poses_;
    haptics::TickOutput out = last_;
    out.status = haptics::TickStatus::kInvalidPose;
    return out;
  }
  if (!feed.connected) {
    has_model_ = false;
    return last_ = Zero(0);
  }
  if (!local_model_) {
    haptics::TickOutput out = Zero(haptics::kConnected);
    for (int i = 0; i < 3; ++i) out.force_n[i] = feed.force_n[i];
    return last_ = out;
  }
  if (feed.stream != stream_) {
    // A new stream seats the device again: the last stream's model is
    // another proxy's.
    stream_ = feed.stream;
    has_model_ = false;
    Reseat();
  }
  if (feed.model_serial != model_serial_ && feed.model_stream == stream_) {
    model_serial_ = feed.model_serial;
    if (loop_.SetModel(feed.model)) has_model_ = true;
  }
  if (!has_model_) return last_ = Zero(haptics::kConnected);
  return last_ = RenderModel(pose);
}

haptics::TickOutput TickRenderer::RenderModel(const haptics::Pose& pose) {
  const double* q = pose.orientation_wxyz;
  Isometry3d X_WD = Isometry3d::Identity();
  X_WD.linear() = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).toRotationMatrix();
  X_WD.translation() = Vector3d(pose.position_m[0], pose.position_m[1], pose.position_m[2]);
  const HapticOutput h = loop_.Tick(X_WD);
  haptics::TickOutput out;
  for (int i = 0; i < 3; ++i) {
    out.force_n[i] = h.force_W[i];
    out.torque_nm[i] = h.torque_W[i];
  }
  out.flags = haptics::kConnected | haptics::kHasModel;
  if (h.touching) out.flags |= haptics::kTouching;
  if (h.clamped) out.flags |= haptics::kClamped;
  if (h.beyond_validity) {
    out.flags |= haptics::kBeyondValidity;
    ++beyond_validity_ticks_;
  }
  return out;
}

}  // namespace hs::sdk

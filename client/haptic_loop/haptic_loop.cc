#include "client/haptic_loop/haptic_loop.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "common/sim/proxy_slide.h"

namespace hs {
namespace {

// The proxy stops this far (relative to the validity radius) in front of a
// plane it meets, so that sliding along it does not meet it again at once;
// the server's proxy keeps a like stand-off relative to the tool's size.
constexpr double kStandOff = 1e-6;

bool Finite(const Isometry3d& X) { return X.matrix().allFinite(); }

bool ValidModel(const LocalModel& m) {
  if (!Finite(m.X_WP) || !m.touch_point_W.allFinite() || !std::isfinite(m.validity_radius_m) ||
      !(m.validity_radius_m > 0) || !std::isfinite(m.force_clamp_n) || !(m.force_clamp_n > 0)) {
    return false;
  }
  return std::all_of(m.planes.begin(), m.planes.end(), [](const ConstraintPlane& p) {
    return p.point_W.allFinite() && p.normal_W.allFinite() && p.tool_point_W.allFinite() &&
           std::abs(p.normal_W.norm() - 1) <= 1e-6 && std::isfinite(p.gap_m) && p.gap_m >= 0 &&
           std::isfinite(p.stiffness_n_per_m) && p.stiffness_n_per_m > 0 &&
           std::isfinite(p.damping_ns_per_m) && p.damping_ns_per_m >= 0 &&
           std::isfinite(p.static_friction) && p.static_friction >= 0 &&
           std::isfinite(p.dynamic_friction) && p.dynamic_friction >= 0 &&
           p.dynamic_friction <= p.static_friction;
  });
}

}  // namespace

bool HapticLoop::SetModel(const LocalModel& model) {
  if (!ValidModel(model)) {
    ++rejected_models_;
    return false;
  }
  pending_model_ = model;
  has_pending_model_ = true;
  return true;
}

int HapticLoop::MoveProxy(const Vector3d& device, const Vector3d& goal_in) {
  const Vector3d P0 = model_.X_WP.translation();
  const double stand_off = kStandOff * model_.validity_radius_m;
  Vector3d p = proxy_;
  Vector3d goal = goal_in;
  int touched = -1;
  for (int slide = 0; slide <= options_.max_slides; ++slide) {
    const Vector3d v = goal - p;
    if (v.norm() <= stand_off * 1e-3) break;
    // The first plane the straight move meets: where the tool's distance in
    // front of it, gap + n . (p - P0), falls to zero.
    int first = -1;
    double first_t = std::numeric_limits<double>::infinity();
    for (int i = 0; i < static_cast<int>(model_.planes.size()); ++i) {
      const ConstraintPlane& plane = model_.planes[i];
      const double approach = plane.normal_W.dot(v);
      if (approach >= 0) continue;
      const double ahead = plane.gap_m + plane.normal_W.dot(p - P0);
      const double t = std::max(ahead, 0.0) / -approach;
      if (t <= 1 && t < first_t) {
        first_t = t;
        first = i;
      }
    }
    if (first < 0) {
      p = goal;
      break;
    }
    const ConstraintPlane& plane = model_.planes[first];
    const Vector3d& n = plane.normal_W;
    p += first_t * v + stand_off * n;
    touched = first;
    // Slide toward the device as the server's proxy does (proxy_slide.h).
    const std::optional<Vector3d> next = SlideGoal(
        p, device, n,
        model_.friction
            ? std::optional<SlideFriction>({plane.static_friction, plane.dynamic_friction})
            : std::nullopt);
    if (!next) break;
    goal = *next;
  }
  // The model holds within its sphere only: the proxy stays inside it.
  const Vector3d out = p - P0;
  if (out.norm() > model_.validity_radius_m) p = P0 + out * (model_.validity_radius_m / out.norm());
  proxy_ = p;
  return touched;
}

HapticOutput HapticLoop::Render(int plane, const Vector3d& device, const Vector3d& v_WD) const {
  HapticOutput out;
  out.p_WP = proxy_;
  if (plane < 0) return out;
  const ConstraintPlane& p = model_.planes[plane];
  out.touching = true;
  // As the server's common/sim/tool_force.h: spring to the proxy, damper
  // along the normal, clamped; the lever is tool-fixed.
  out.force_W = p.stiffness_n_per_m * (proxy_ - device) -
                p.damping_ns_per_m * v_WD.dot(p.normal_W) * p.normal_W;
  if (out.force_W.norm() > model_.force_clamp_n) {
    out.force_W *= model_.force_clamp_n / out.force_W.norm();
    out.clamped = true;
  }
  const Vector3d& lever_end = model_.touching ? model_.touch_point_W : p.tool_point_W;
  out.torque_W = (lever_end - model_.X_WP.translation()).cross(out.force_W);
  return out;
}

HapticOutput HapticLoop::Step(const Vector3d& device, const Vector3d& v_WD) {
  // Past the validity sphere the model says nothing: the proxy goes no
  // farther than its edge.
  const Vector3d P0 = model_.X_WP.translation();
  const Vector3d from_proxy = device - P0;
  const bool beyond = from_proxy.norm() > model_.validity_radius_m;
  const Vector3d goal =
      beyond ? Vector3d(P0 + from_proxy * (model_.validity_radius_m / from_proxy.norm())) : device;
  HapticOutput out = Render(MoveProxy(device, goal), device, v_WD);
  out.beyond_validity = beyond;
  return out;
}

HapticOutput HapticLoop::Tick(const Isometry3d& X_WD) {
  if (!Finite(X_WD)) {
    ++rejected_poses_;
    return last_;
  }
  const Vector3d device = X_WD.translation();
  const Vector3d v_WD =
      has_last_device_ ? Vector3d((device - last_device_) / options_.tick_s) : Vector3d::Zero();
  last_device_ = device;
  has_last_device_ = true;
  HapticOutput out;
  if (has_pending_model_) {
    // What the old model renders at this pose, against what the new one
    // does from the server's proxy: that step, not the hand's motion, is
    // what gets spread over the next ticks.
    const Vector3d before = has_model_ ? Step(device, v_WD).force_W : last_.force_W;
    std::swap(model_, pending_model_);
    has_pending_model_ = false;
    has_model_ = true;
    proxy_ = model_.X_WP.translation();
    out = Step(device, v_WD);
    switch_offset_ += before - out.force_W;
  } else if (has_model_) {
    out = Step(device, v_WD);
  } else {
    proxy_ = device;
    out.p_WP = device;
  }
  if (out.beyond_validity) ++beyond_validity_ticks_;
  const double left = switch_offset_.norm();
  if (left <= options_.max_switch_step_n) {
    switch_offset_.setZero();
  } else {
    switch_offset_ *= (left - options_.max_switch_step_n) / left;
  }
  out.force_W += switch_offset_;
  last_ = out;
  return out;
}

}  // namespace hs

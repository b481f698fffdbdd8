#include "common/sim/tool_force.h"

namespace hs {
namespace {

// Scales `force` down to `clamp_n` newtons when longer; true when it did.
bool Clamp(Vector3d& force, double clamp_n) {
  if (force.norm() <= clamp_n) return false;
  force *= clamp_n / force.norm();
  return true;
}

// x and y in series; 0 when either is 0.
double InSeries(double x, double y) { return x > 0 && y > 0 ? x * y / (x + y) : 0.0; }

}  // namespace

Material TouchingMaterial(const Material& own, const Material& touched) {
  return Material{.name = "",
                  .stiffness_n_per_m = InSeries(own.stiffness_n_per_m, touched.stiffness_n_per_m),
                  .damping_ns_per_m = InSeries(own.damping_ns_per_m, touched.damping_ns_per_m),
                  .static_friction = touched.static_friction,
                  .dynamic_friction = touched.dynamic_friction};
}

ToolForce SpringDamperForce(const Material& material, const ToolContact& contact, double clamp_n) {
  ToolForce out;
  // Spring toward the proxy; damping of the device's speed along the normal.
  out.force_W = material.stiffness_n_per_m * (contact.p_WP - contact.p_WD) -
                material.damping_ns_per_m * contact.v_WD.dot(contact.normal_W) * contact.normal_W;
  out.clamped = Clamp(out.force_W, clamp_n);
  out.torque_W = (contact.p_WC - contact.p_WP).cross(out.force_W);
  return out;
}

ToolForce WithReaction(ToolForce force, const ToolForce& reaction, double clamp_n) {
  force.force_W += reaction.force_W;
  force.torque_W += reaction.torque_W;
  force.clamped = Clamp(force.force_W, clamp_n) || force.clamped;
  return force;
}

ToolForce WithPushReaction(ToolForce force, const Vector3d& push_impulse_W, double step_s,
                           double clamp_n) {
  if (push_impulse_W.isZero()) return force;
  return WithReaction(force, {.force_W = -push_impulse_W / step_s}, clamp_n);
}

}  // namespace hs

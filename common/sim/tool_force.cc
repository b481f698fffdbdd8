#include "common/sim/tool_force.h"

namespace hs {
namespace {

// Scales `force` down to `clamp_n` newtons when longer; true when it did.
bool Clamp(Vector3d& force, double clamp_n) {
  if (force.norm() <= clamp_n) return false;
  force *= clamp_n / force.norm();
  return true;
}

}  // namespace

ToolForce SpringDamperForce(const Material& material, const ToolContact& contact, double clamp_n) {
  ToolForce out;
  // Spring toward the proxy; damping of the device's speed along the normal.
  out.force_W = material.stiffness_n_per_m * (contact.p_WP - contact.p_WD) -
                material.damping_ns_per_m * contact.v_WD.dot(contact.normal_W) * contact.normal_W;
  out.clamped = Clamp(out.force_W, clamp_n);
  out.torque_W = (contact.p_WC - contact.p_WP).cross(out.force_W);
  return out;
}

ToolForce WithPushReaction(ToolForce force, const Vector3d& push_impulse_W, double step_s,
                           double clamp_n) {
  if (push_impulse_W.isZero()) return force;
  force.force_W -= push_impulse_W / step_s;
  force.clamped = Clamp(force.force_W, clamp_n) || force.clamped;
  return force;
}

}  // namespace hs

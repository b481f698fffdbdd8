#include "common/sim/tool_force.h"

namespace hs {

ToolForce SpringDamperForce(const Material& material, const ToolContact& contact, double clamp_n) {
  ToolForce out;
  // Spring toward the proxy; damping of the device's speed along the normal.
  out.force_W = material.stiffness_n_per_m * (contact.p_WP - contact.p_WD) -
                material.damping_ns_per_m * contact.v_WD.dot(contact.normal_W) * contact.normal_W;
  if (out.force_W.norm() > clamp_n) {
    out.force_W *= clamp_n / out.force_W.norm();
    out.clamped = true;
  }
  out.torque_W = (contact.p_WC - contact.p_WP).cross(out.force_W);
  return out;
}

}  // namespace hs

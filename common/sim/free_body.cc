#include "common/sim/free_body.h"

#include <cmath>

namespace hs {
void IntegrateFreeBody(const MassProperties& body, const Vector3d& g_W, double dt_s,
                       FreeBodyState& state) {
  state.v_W += dt_s * g_W;
  const Vector3d p_WC = CentreOfMass(body, state) + dt_s * state.v_W;
  const double angle = state.w_W.norm() * dt_s;
  Eigen::Quaterniond q(state.X_WO.linear());
  if (angle > 0) q = Eigen::Quaterniond(Eigen::AngleAxisd(angle, state.w_W.normalized())) * q;
  q.normalize();
  state.X_WO.linear() = q.toRotationMatrix();
  state.X_WO.translation() = p_WC - state.X_WO.linear() * body.p_OC;
}

}  // namespace hs

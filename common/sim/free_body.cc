#include "common/sim/free_body.h"

#include <algorithm>
#include <cmath>
#include <optional>

namespace hs {
namespace {

// How one body answers an impulse at a point of it.
struct ImpulseTarget {
  const MassProperties* mass = nullptr;
  FreeBodyState* state = nullptr;
  Vector3d r = Vector3d::Zero();  // lever arm from the centre of mass, world
  Matrix3d inverse_I_W = Matrix3d::Zero();

  ImpulseTarget(const MassProperties& m, FreeBodyState& s, const Vector3d& p_WC)
      : mass(&m), state(&s), r(p_WC - CentreOfMass(m, s)) {
    const Matrix3d R = s.X_WO.linear();
    inverse_I_W = R * m.I_C.inverse() * R.transpose();
  }
  Vector3d PointVelocity() const { return state->v_W + state->w_W.cross(r); }
  // The velocity change at the point along unit u per unit impulse along u.
  double Response(const Vector3d& u) const {
    return 1 / mass->mass_kg + u.dot((inverse_I_W * r.cross(u)).cross(r));
  }
  // Applies `impulse` at the point, or through the centre of mass.
  void Apply(const Vector3d& impulse, bool at_point) const {
    state->v_W += impulse / mass->mass_kg;
    if (at_point) state->w_W += inverse_I_W * r.cross(impulse);
  }
};

}  // namespace

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

Vector3d RespondToContact(const MassProperties& body, const BodyContact& contact,
                          FreeBodyState& state, const OtherBody& other) {
  const Vector3d& n = contact.normal_W;
  if (contact.separation_m > 0) {
    // Two free bodies part by inverse mass: a light body on a heavy one
    // moves most, and neither is shoved whole into what lies behind it.
    const double share =
        other.mass == nullptr ? 1.0 : other.mass->mass_kg / (body.mass_kg + other.mass->mass_kg);
    state.X_WO.translation() += share * contact.separation_m * n;
    if (other.state != nullptr) {
      other.state->X_WO.translation() -= (1 - share) * contact.separation_m * n;
    }
  }
  const ImpulseTarget self(body, state, contact.p_WC);
  std::optional<ImpulseTarget> that;
  if (other.mass != nullptr) that.emplace(*other.mass, *other.state, contact.p_WC);
  const Vector3d v_other = that ? that->PointVelocity() : contact.v_other_W;
  const Vector3d v_rel = self.PointVelocity() - v_other;
  const double approach = v_rel.dot(n);
  if (approach >= 0 && contact.grip_impulse <= 0) return Vector3d::Zero();
  auto response = [&](const Vector3d& u) {
    return self.Response(u) + (that ? that->Response(u) : 0.0);
  };
  const double normal_impulse = approach < 0 ? -approach / response(n) : 0.0;
  const Vector3d normal = normal_impulse * n;
  if (normal_impulse > 0) {
    self.Apply(normal, true);
    if (that) that->Apply(-normal, true);
  }
  // Friction: the impulse that stops the sliding, limited to the cone. It
  // goes through the centres of mass: with one impulse point per contact
  // the normal force cannot shift to balance friction's tipping moment, so
  // friction at the contact point would make a sliding box rock.
  Vector3d friction = Vector3d::Zero();
  const Vector3d v_t = v_rel - approach * n;
  const double speed_t = v_t.norm();
  if (speed_t > 0 && contact.friction > 0) {
    const double linear = 1 / body.mass_kg + (that ? 1 / that->mass->mass_kg : 0.0);
    friction =
        -std::min(speed_t / linear, contact.friction * (normal_impulse + contact.grip_impulse)) *
        (v_t / speed_t);
    self.Apply(friction, false);
    if (that) that->Apply(-friction, false);
  }
  const Vector3d impulse = normal + friction;
  return impulse;
}

}  // namespace hs

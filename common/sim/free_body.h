#pragma once
// Rigid-body motion of a free object: semi-implicit (symplectic) Euler
// steps under gravity. Its contacts are solved together by the contact
// solver (contact_solver.h).

#include "common/sim/mass_properties.h"

namespace hs {

/// The state of one free body.
struct FreeBodyState {
  /// X_WO: the object frame in the world, metres.
  Isometry3d X_WO = Isometry3d::Identity();
  /// Velocity of the centre of mass, world frame, m/s.
  Vector3d v_W = Vector3d::Zero();
  /// Angular velocity, world frame, rad/s.
  Vector3d w_W = Vector3d::Zero();
};

/// The centre of mass in the world, metres.
inline Vector3d CentreOfMass(const MassProperties& body, const FreeBodyState& state) {
  return state.X_WO * body.p_OC;
}

/// Semi-implicit Euler over `dt_s` seconds: the velocity takes the
/// acceleration `g_W` (world frame, m/s^2) first, then the pose moves with
/// the new velocities (the rotation about the centre of mass, kept
/// orthonormal through a unit quaternion). Gyroscopic torque is left out.
void IntegrateFreeBody(const MassProperties& body, const Vector3d& g_W, double dt_s,
                       FreeBodyState& state);

}  // namespace hs

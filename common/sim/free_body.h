#pragma once
// Rigid-body motion of a free object: semi-implicit (symplectic) Euler
// steps under gravity, and the response to one contact: the body is moved
// out along the contact normal by the normal share of the reversing vector
// and takes an inelastic impulse with Coulomb friction at the contact.

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

/// One contact of a free body with another object, as the response sees it.
struct BodyContact {
  /// Unit normal, world frame, pointing from the other object to the body.
  Vector3d normal_W = Vector3d::UnitZ();
  /// Where the impulse acts (the contact points' centroid), world, metres.
  Vector3d p_WC = Vector3d::Zero();
  /// How far to move the body along normal_W to stop penetrating, metres
  /// (the normal share of the reversing vector); 0 when only touching.
  double separation_m = 0;
  /// Velocity of the other object's material at p_WC, world frame, m/s.
  Vector3d v_other_W = Vector3d::Zero();
  /// Coulomb coefficient for the tangential impulse, >= 0.
  double friction = 0;
  /// How hard the other object squeezes the body beyond stopping its
  /// approach over this (sub-)step, N*s: a tool whose device is in the
  /// body, its stiffness times the depth times the sub-step. It widens
  /// friction's cone, so that two tools pinching a body hold it up; it
  /// does not move the body (the separation does), and the tool feels it
  /// back.
  double grip_impulse = 0;
};

/// The other object of a contact when it is a free body too.
struct OtherBody {
  const MassProperties* mass = nullptr;
  FreeBodyState* state = nullptr;
};

/// Moves the body out along the normal (a free `other` takes its share of
/// the separation by inverse mass), then, when it approaches the other
/// object at the contact point, applies the impulse that stops the
/// approach (restitution 0) at the contact point; friction's impulse, at
/// most `friction` times the normal one and the grip, acts through the
/// centre of mass (with a grip, also when not approaching). A fixed object or a tool
/// (no `other`) does not give way: contact.v_other_W is its velocity. A free `other` takes the
/// opposite impulse, its velocity read from its state. Returns the impulse applied to the body,
/// world frame, N*s.
Vector3d RespondToContact(const MassProperties& body, const BodyContact& contact,
                          FreeBodyState& state, const OtherBody& other = {});

}  // namespace hs

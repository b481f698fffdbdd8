#pragma once
// Mass, centre of mass and rotational inertia of a rigid object from its
// closed triangle mesh (uniform density), for free-body motion.

#include "absl/status/statusor.h"
#include "common/hds/haptic_object.h"

namespace hs {

/// The lightest and heaviest free body, kilograms: a tenth of a gram to a
/// million tonnes. Bodies of 1e-300 and 1e300 kg ended their first steps
/// with NaN poses, and bodies under 0.1 g pushed by a tool at 0.2 m/s flew
/// off the floor; at both bounds they stay on it (free_bodies_test).
inline constexpr double kMinBodyMassKg = 1e-4;
inline constexpr double kMaxBodyMassKg = 1e9;

/// A rigid body's inertia, in its object frame O.
struct MassProperties {
  /// Mass, kilograms, > 0.
  double mass_kg = 1;
  /// Centre of mass p_OC, object frame, metres.
  Vector3d p_OC = Vector3d::Zero();
  /// Rotational inertia about the centre of mass, axes of frame O, kg*m^2.
  Matrix3d I_C = Matrix3d::Identity();
};

/// The mass properties of `object` as a solid of uniform density. When
/// `mass_kg` > 0 it is the body's mass; otherwise the mass is
/// `density_kg_per_m3` times the enclosed volume. A mesh that encloses no
/// volume (open, flat, inside out) is taken as its solid bounding box.
/// INVALID_ARGUMENT when neither number is finite and > 0, or the mass
/// is outside [kMinBodyMassKg, kMaxBodyMassKg].
absl::StatusOr<MassProperties> ComputeMassProperties(const HapticObject& object, double mass_kg,
                                                     double density_kg_per_m3);

}  // namespace hs

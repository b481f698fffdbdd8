#pragma once
// Haptic material of a group of faces (paper s.2: material properties live on
// element plates, not on vertices).

#include <string>

#include "absl/status/status.h"

namespace hs {

/// The largest stiffness, damping and friction coefficient a material
/// takes: far past any surface a device renders, and low enough that a
/// force, its damping and its friction stay finite for every motion a
/// scene admits (a 1e308 N/m surface gave a NaN force).
inline constexpr double kMaxStiffnessNPerM = 1e9;
inline constexpr double kMaxDampingNsPerM = 1e9;
inline constexpr double kMaxFriction = 1e3;

/// What a face feels like when touched. All values are per contact.
struct Material {
  /// Name from the model file (or "default"); one face group per name.
  std::string name = "default";
  /// Spring constant of the surface, N/m. In (0, kMaxStiffnessNPerM].
  double stiffness_n_per_m = 1000.0;
  /// Viscous damping along the contact normal, N*s/m. In [0, kMaxDampingNsPerM].
  double damping_ns_per_m = 1.0;
  /// Coulomb static friction coefficient, dimensionless. In [0, kMaxFriction].
  double static_friction = 0.3;
  /// Coulomb dynamic friction coefficient, dimensionless, 0 <= it <= static_friction.
  double dynamic_friction = 0.2;

  bool operator==(const Material&) const = default;
};

/// INVALID_ARGUMENT naming the first field out of its documented range.
absl::Status ValidateMaterial(const Material& material);

}  // namespace hs

#pragma once
// Haptic material of a group of faces (paper s.2: material properties live on
// element plates, not on vertices).

#include <string>

#include "absl/status/status.h"

namespace hs {

/// What a face feels like when touched. All values are per contact.
struct Material {
  /// Name from the model file (or "default"); one face group per name.
  std::string name = "default";
  /// Spring constant of the surface, N/m. Finite and > 0.
  double stiffness_n_per_m = 1000.0;
  /// Viscous damping along the contact normal, N*s/m. Finite and >= 0.
  double damping_ns_per_m = 1.0;
  /// Coulomb static friction coefficient, dimensionless. Finite and >= 0.
  double static_friction = 0.3;
  /// Coulomb dynamic friction coefficient, dimensionless, 0 <= it <= static_friction.
  double dynamic_friction = 0.2;

  bool operator==(const Material&) const = default;
};

/// INVALID_ARGUMENT naming the first field out of its documented range.
absl::Status ValidateMaterial(const Material& material);

}  // namespace hs

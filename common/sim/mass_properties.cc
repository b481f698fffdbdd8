#include "common/sim/mass_properties.h"

#include <cmath>

#include "absl/strings/str_cat.h"

namespace hs {
namespace {

// Volume, first moment and second moment (sum of p p^T dV) of a body of
// unit density.
struct Moments {
  double volume = 0;
  Vector3d first = Vector3d::Zero();
  Matrix3d second = Matrix3d::Zero();
};

// Sums the signed tetrahedra from the origin to each face (divergence
// theorem): exact for a closed, outward-oriented mesh.
Moments MeshMoments(const HapticObject& object) {
  // Second moment of the unit tetrahedron (0, e1, e2, e3) over its volume x 6.
  Matrix3d canonical;
  canonical << 2, 1, 1, 1, 2, 1, 1, 1, 2;
  canonical /= 120.0;
  Moments m;
  for (const Face& f : object.faces()) {
    Matrix3d A;
    A << object.position(f.vertices[0]), object.position(f.vertices[1]),
        object.position(f.vertices[2]);
    const double det = A.determinant();
    m.volume += det / 6;
    m.first += det / 24 * A.rowwise().sum();
    m.second += det * A * canonical * A.transpose();
  }
  return m;
}

Moments BoxMoments(const AlignedBox3d& box) {
  const Vector3d size = box.sizes();
  const Vector3d c = box.center();
  Moments m;
  m.volume = size.prod();
  m.first = m.volume * c;
  m.second = m.volume * (Matrix3d(size.cwiseAbs2().asDiagonal()) / 12 + c * c.transpose());
  return m;
}

}  // namespace

absl::StatusOr<MassProperties> ComputeMassProperties(const HapticObject& object, double mass_kg,
                                                     double density_kg_per_m3) {
  const bool by_mass = std::isfinite(mass_kg) && mass_kg > 0;
  if (!by_mass && !(std::isfinite(density_kg_per_m3) && density_kg_per_m3 > 0)) {
    return absl::InvalidArgumentError("a free body needs a mass or density that is finite and > 0");
  }
  Moments m = MeshMoments(object);
  // Below this share of its box, the mesh is taken as enclosing nothing.
  constexpr double kMinVolumeShare = 1e-9;
  const double box_volume = object.bounding_box().sizes().prod();
  if (!(m.volume > kMinVolumeShare * box_volume)) m = BoxMoments(object.bounding_box());
  if (!(m.volume > 0)) {
    return absl::InvalidArgumentError("a free body's mesh and box enclose no volume");
  }
  MassProperties out;
  out.mass_kg = by_mass ? mass_kg : density_kg_per_m3 * m.volume;
  if (!(out.mass_kg >= kMinBodyMassKg && out.mass_kg <= kMaxBodyMassKg)) {
    return absl::InvalidArgumentError(absl::StrCat("a free body's mass, ", out.mass_kg,
                                                   " kg, must be in [", kMinBodyMassKg, ", ",
                                                   kMaxBodyMassKg, "] kg"));
  }
  const double density = out.mass_kg / m.volume;
  out.p_OC = m.first / m.volume;
  // Second moment about the centre of mass, then the inertia tensor.
  const Matrix3d second = density * m.second - out.mass_kg * out.p_OC * out.p_OC.transpose();
  out.I_C = second.trace() * Matrix3d::Identity() - second;
  return out;
}

}  // namespace hs

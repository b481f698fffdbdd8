#pragma once
// Predicates on single triangles shared by validation and cleaning.

#include "common/core/types.h"

namespace hs {

/// True when triangle (a, b, c) has zero area up to rounding: twice its area
/// is at most 1e-12 times the square of its longest edge (a relative test,
/// so it holds at every scale).
inline bool IsDegenerateTriangle(const Vector3d& a, const Vector3d& b, const Vector3d& c) {
  const double longest_sq =
      std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
  return (b - a).cross(c - a).norm() <= 1e-12 * longest_sq;
}

}  // namespace hs

#pragma once
// Triangles that the batched kernels' tests compare with the scalar code
// (plane_bounds_batch_test, face_test_batch_test): random ones at a scale,
// and faces on a small grid, whose corners make parallel, coplanar and
// touching faces common, with a line and a point among them.

#include <random>
#include <vector>

#include "common/collision/triangle_sat.h"

namespace hs::testing {

/// Corners uniform in the cube of half-side `scale` about `offset`.
inline Triangle3d RandomTriangle(std::mt19937& rng, double scale, const Vector3d& offset) {
  std::uniform_real_distribution<double> u(-1, 1);
  Triangle3d t;
  for (Vector3d& p : t) p = scale * Vector3d(u(rng), u(rng), u(rng)) + offset;
  return t;
}

/// 13 pairs (a[i], b[i]) of faces with corners on the grid {-2, ..., 2}^3;
/// a line and a point are among each side's faces (no usable normal).
struct GridPairs {
  std::vector<Triangle3d> a, b;
};
inline GridPairs GridAndDegeneratePairs(std::mt19937& rng) {
  std::uniform_int_distribution<int> c(-2, 2);
  auto grid = [&] {
    Triangle3d t;
    for (Vector3d& p : t) p = Vector3d(c(rng), c(rng), c(rng));
    return t;
  };
  const Triangle3d line = {Vector3d(0, 0, 0), Vector3d(1, 1, 1), Vector3d(2, 2, 2)};
  const Triangle3d point = {Vector3d(1, 0, 0), Vector3d(1, 0, 0), Vector3d(1, 0, 0)};
  GridPairs pairs;
  for (int i = 0; i < 11; ++i) pairs.b.push_back(grid());
  pairs.b.push_back(line);
  pairs.b.push_back(point);
  for (int i = 0; i < 13; ++i) pairs.a.push_back(i % 5 == 4 ? line : i % 7 == 6 ? point : grid());
  return pairs;
}

}  // namespace hs::testing

#pragma once
// The contact locator's first tests as their definitions say
// (near_features_batch.h), with Eigen, a comparison at a time: the oracle
// of the lanes, in near_features_batch_test and the kernels fuzzer.

#include <algorithm>
#include <cmath>

#include "common/contact/near_features_batch.h"

namespace hs::testing {

inline NearFeatures NearFeaturesOracle(const Triangle3d& m, const FixedFaceEdges& f, double tol,
                                       double slack) {
  NearFeatures out;
  double off[3];
  for (int i = 0; i < 3; ++i) {
    off[i] = f.unit_normal.dot(m[i] - f.corners[0]);
    if (!(std::abs(off[i]) > tol)) out.moving_corners |= 1 << i;
  }
  for (int i = 0; i < 3; ++i) {
    const int k = (i + 1) % 3;
    const bool beyond = (off[i] > tol && off[k] > tol) || (off[i] < -tol && off[k] < -tol);
    if (!beyond) out.moving_edges |= 1 << i;
  }
  Vector3d lo, hi;
  for (int d = 0; d < 3; ++d) {
    lo[d] = std::min(std::min(m[0][d], m[1][d]), m[2][d]);
    hi[d] = std::max(std::max(m[0][d], m[1][d]), m[2][d]);
  }
  for (int j = 0; j < 3; ++j) {
    const Vector3d& p = f.corners[j];
    if ((p.array() >= lo.array() - slack).all() && (p.array() <= hi.array() + slack).all()) {
      out.fixed_corners |= 1 << j;
    }
  }
  if (out.moving_edges == 0) return out;
  // Beside edge j: every corner of m more than twice the tolerance on one
  // side (a NaN distance is on neither).
  for (int j = 0; j < 3; ++j) {
    bool above = true, below = true;
    for (int i = 0; i < 3; ++i) {
      const double d = f.across[j].dot(m[i] - f.corners[j]);
      above = above && d > 2 * tol;
      below = below && d < -2 * tol;
    }
    if (!(above || below)) out.fixed_edges |= 1 << j;
  }
  return out;
}

/// Whether two answers are the same, bit by bit.
inline bool SameNearFeatures(const NearFeatures& x, const NearFeatures& y) {
  return x.moving_corners == y.moving_corners && x.moving_edges == y.moving_edges &&
         x.fixed_corners == y.fixed_corners && x.fixed_edges == y.fixed_edges;
}

}  // namespace hs::testing

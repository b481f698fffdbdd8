#pragma once
// Test helpers for the edge pair tests: random edges, and where a test's
// answer flips as an edge is shifted.

#include <cmath>
#include <functional>
#include <random>
#include <vector>

#include "common/sim/edge_pairs.h"

namespace hs::testing_edges {

inline Vector3d RandomUnit(std::mt19937& rng) {
  std::normal_distribution<double> g;
  return Vector3d(g(rng), g(rng), g(rng)).normalized();
}

/// A random edge within `scale` of `offset`: length up to `scale`, its
/// `out` any way.
inline WorldEdge RandomEdge(std::mt19937& rng, double scale,
                            const Vector3d& offset = Vector3d::Zero()) {
  std::uniform_real_distribution<double> u(-1, 1), l(0.05, 1);
  const Vector3d from = offset + scale * Vector3d(u(rng), u(rng), u(rng));
  return {from, from + scale * l(rng) * RandomUnit(rng), RandomUnit(rng)};
}

/// `e` moved by s along `direction`.
inline WorldEdge Shifted(const WorldEdge& e, double s, const Vector3d& direction) {
  return {e.from + s * direction, e.to + s * direction, e.out};
}

/// The shifts s in (0, 5 cm] where answer(s) first differs from answer(0),
/// bisected to two adjacent doubles lo < hi (answer(lo) == answer(0));
/// false when it never does.
inline bool FindFlip(const std::function<bool(double)>& answer, double& lo, double& hi) {
  lo = hi = 0;
  for (double s = 0.0005; s <= 0.05; s += 0.0005) {
    if (answer(s) != answer(0)) {
      hi = s;
      break;
    }
    lo = s;
  }
  if (hi == 0) return false;
  for (int k = 0; k < 200 && std::nextafter(lo, hi) != hi; ++k) {
    const double mid = lo + (hi - lo) / 2;
    (answer(mid) == answer(lo) ? lo : hi) = mid;
  }
  return true;
}

/// The 13 doubles from 6 below `at` to 6 above it.
inline std::vector<double> DoublesAround(double at) {
  double s = at;
  for (int k = 0; k < 6; ++k) s = std::nextafter(s, -HUGE_VAL);
  std::vector<double> out;
  for (int k = 0; k < 13; ++k, s = std::nextafter(s, HUGE_VAL)) out.push_back(s);
  return out;
}

}  // namespace hs::testing_edges

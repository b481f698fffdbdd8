#include "common/hds/weld.h"

#include <gtest/gtest.h>

#include <random>

namespace hs {
namespace {

// The oracle: every vertex against every earlier kept vertex, in order.
std::vector<VertexId> BruteForceTargets(const std::vector<Vector3d>& p, double tolerance) {
  std::vector<VertexId> target(p.size());
  for (size_t v = 0; v < p.size(); ++v) {
    target[v] = static_cast<VertexId>(v);
    for (size_t u = 0; u < v; ++u) {
      if (target[u] == static_cast<VertexId>(u) && (p[u] - p[v]).norm() <= tolerance) {
        target[v] = static_cast<VertexId>(u);
        break;
      }
    }
  }
  return target;
}

// The grid finds the same duplicates as the brute-force oracle, for points
// whose duplicates sit well inside or well outside the tolerance.
TEST(WeldTest, AgreesWithBruteForce) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coordinate(-1, 1);
  std::uniform_real_distribution<double> jitter(-1, 1);
  for (double scale : {1e-4, 1.0, 1e4}) {
    SCOPED_TRACE(scale);
    const double tolerance = 1e-6 * scale;
    std::vector<Vector3d> p;
    for (int i = 0; i < 400; ++i) {
      p.push_back(scale * Vector3d(coordinate(rng), coordinate(rng), coordinate(rng)));
      if (i % 3 == 0) {
        // A near copy at a fifth of the tolerance: must weld.
        p.push_back(p.back() +
                    0.2 * tolerance * Vector3d(jitter(rng), jitter(rng), jitter(rng)).normalized());
      }
      if (i % 5 == 0) {
        // A copy at three times the tolerance: must stay.
        p.push_back(p.back() + 3 * tolerance * Vector3d::UnitX());
      }
    }
    EXPECT_EQ(FindWeldTargets(p, tolerance), BruteForceTargets(p, tolerance));
  }
}

// Zero tolerance welds only exact copies.
TEST(WeldTest, ZeroToleranceWeldsExactCopies) {
  const std::vector<Vector3d> p = {{0, 0, 0}, {1, 0, 0}, {0, 0, 0}, {1, 0, 1e-12}};
  const std::vector<VertexId> expected = {0, 1, 0, 3};
  EXPECT_EQ(FindWeldTargets(p, 0.0), expected);
}

}  // namespace
}  // namespace hs

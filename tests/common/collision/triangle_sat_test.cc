#include "common/collision/triangle_sat.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/intersections.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <utility>

namespace hs {
namespace {

using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;

Kernel::Triangle_3 ToCgal(const Triangle3d& t) {
  auto p = [](const Vector3d& v) { return Kernel::Point_3(v.x(), v.y(), v.z()); };
  return Kernel::Triangle_3(p(t[0]), p(t[1]), p(t[2]));
}

// Triangles with small integer corners: every product in the SAT is exact in
// double, and the grid makes touching, coplanar and parallel-edge cases common.
Triangle3d RandomGridTriangle(std::mt19937& rng) {
  std::uniform_int_distribution<int> c(-2, 2);
  while (true) {
    Triangle3d t;
    for (Vector3d& p : t) p = Vector3d(c(rng), c(rng), c(rng));
    if ((t[1] - t[0]).cross(t[2] - t[0]).squaredNorm() > 0) return t;
  }
}

// With zero margin the SAT test agrees exactly with CGAL's exact predicate
// on 20,000 grid triangle pairs, touching and coplanar ones included.
TEST(TriangleSatTest, AgreesWithCgalExactPredicate) {
  std::mt19937 rng(11);
  int intersecting = 0, touching_or_coplanar = 0;
  for (int i = 0; i < 20000; ++i) {
    const Triangle3d a = RandomGridTriangle(rng), b = RandomGridTriangle(rng);
    const bool exact = CGAL::do_intersect(ToCgal(a), ToCgal(b));
    ASSERT_EQ(TrianglesIntersect(a, b, 0.0), exact) << "pair " << i;
    intersecting += exact;
    const Vector3d na = (a[1] - a[0]).cross(a[2] - a[0]);
    touching_or_coplanar += exact && na.dot(b[0] - a[0]) == 0;
  }
  // The sample must exercise both answers and the coplanar/touching case.
  EXPECT_GT(intersecting, 2000);
  EXPECT_LT(intersecting, 18000);
  EXPECT_GT(touching_or_coplanar, 200);
}

// The sweep interval says where a translated triangle meets the other:
// inside it the static test (CGAL, exact) says intersect, outside it not.
TEST(TriangleSatTest, SweptIntervalMatchesStaticTests) {
  std::mt19937 rng(12);
  std::uniform_int_distribution<int> c(-2, 2);
  int nonempty = 0;
  for (int i = 0; i < 2000; ++i) {
    const Triangle3d a = RandomGridTriangle(rng), b = RandomGridTriangle(rng);
    Vector3d d(c(rng), c(rng), c(rng));
    if (d.isZero()) d = Vector3d::UnitX();
    const Interval interval = SweptIntersection(a, b, d, 0.0);
    nonempty += !interval.empty();
    // Sample t on a grid of quarters: a - t d stays exactly representable.
    for (int k = -24; k <= 24; ++k) {
      const double t = k / 4.0;
      Triangle3d moved = a;
      for (Vector3d& p : moved) p -= t * d;
      const bool exact = CGAL::do_intersect(ToCgal(moved), ToCgal(b));
      // Endpoints are computed with one rounding; give them 1e-9 of slack.
      if (std::abs(t - interval.lo) < 1e-9 || std::abs(t - interval.hi) < 1e-9) continue;
      ASSERT_EQ(interval.Contains(t), exact) << "pair " << i << " t " << t << " interval ["
                                             << interval.lo << ", " << interval.hi << "]";
    }
  }
  EXPECT_GT(nonempty, 500);
}

// A pair of unit-sized triangles with real-valued corners, the second
// within about its size of the first: crossings, near misses and gaps,
// none on a grid.
std::pair<Triangle3d, Triangle3d> RandomNearbyPair(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  auto random = [&] { return Vector3d(u(rng), u(rng), u(rng)); };
  const Vector3d offset = 0.8 * random();
  Triangle3d a, b;
  for (int i = 0; i < 3; ++i) {
    a[i] = random();
    b[i] = random() + offset;
  }
  return {a, b};
}

// TrianglesIntersect answers most pairs before its axis loop (the plane
// tests, Moller's crossing, the edge pair facing across the common line).
// Each fast answer must be the one the whole axis set gives: the swept
// test at t = 0 runs every axis and nothing else.
TEST(TriangleSatTest, FastAnswersAgreeWithEveryAxis) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> u(-1, 1);
  int meeting = 0;
  for (int i = 0; i < 20000; ++i) {
    const auto [a, b] = RandomNearbyPair(rng);
    const Vector3d direction(u(rng), u(rng), u(rng));
    for (double margin : {0.0, 1e-3, 0.05}) {
      const bool every_axis = !SweptIntersection(a, b, direction, margin, {0, 0}).empty();
      ASSERT_EQ(TrianglesIntersect(a, b, margin), every_axis)
          << "pair " << i << " margin " << margin;
      meeting += every_axis;
    }
  }
  EXPECT_GT(meeting, 6000);
  EXPECT_LT(meeting, 54000);
}

// A resting contact's faces: one triangle touches the other's plane at a
// corner (put on the plane, so within a rounding of it), the rest of it to
// one side, the corner inside or outside the other triangle. Here the
// crossing test cannot answer (a corner is on the plane) and the plane
// tests can, wrongly, if they round unlike the axes: the answer must be the
// whole axis set's, both ways round, for touching pairs that meet and ones
// that do not. Not at zero margin: there the corner's rounding off the
// plane decides, differently along differently rounded axes
// (AgreesWithCgalExactPredicate covers exact touching).
TEST(TriangleSatTest, TouchingCornerAnswersAgreeWithEveryAxis) {
  std::mt19937 rng(14);
  std::uniform_real_distribution<double> u(-1, 1);
  int meeting = 0, apart = 0;
  for (int i = 0; i < 20000; ++i) {
    const Triangle3d b = {Vector3d(u(rng), u(rng), 0.3 * u(rng)),
                          Vector3d(u(rng), u(rng), 0.3 * u(rng)),
                          Vector3d(u(rng), u(rng), 0.3 * u(rng))};
    const Vector3d n = TriangleNormal(b).normalized();
    // A point of b's plane, inside b or around it.
    std::uniform_real_distribution<double> w(-0.5, 1.5);
    const Vector3d corner = b[0] + w(rng) * (b[1] - b[0]) + w(rng) * (b[2] - b[0]);
    const double side = u(rng) < 0 ? -1 : 1;
    // Off the plane on the chosen side: a random offset along it, then away.
    auto off_plane = [&]() -> Vector3d {
      Vector3d along(u(rng), u(rng), u(rng));
      along -= along.dot(n) * n;
      return corner + along + side * (0.05 + std::abs(u(rng))) * n;
    };
    const Triangle3d a = {corner, off_plane(), off_plane()};
    const Vector3d direction(u(rng), u(rng), u(rng));
    for (double margin : {1e-9, 1e-3}) {
      const bool every_axis = !SweptIntersection(a, b, direction, margin, {0, 0}).empty();
      ASSERT_EQ(TrianglesIntersect(a, b, margin), every_axis)
          << "pair " << i << " margin " << margin;
      ASSERT_EQ(TrianglesIntersect(b, a, margin), every_axis)
          << "pair " << i << " margin " << margin;
      meeting += every_axis;
      apart += !every_axis;
    }
  }
  EXPECT_GT(meeting, 2000);
  EXPECT_GT(apart, 2000);
}

// SweptPlaneBounds holds SweptIntersection at zero margin and at the
// margin, and is looser than it.
TEST(TriangleSatTest, PlaneBoundsHoldTheIntervals) {
  std::mt19937 rng(14);
  std::uniform_real_distribution<double> u(-1, 1);
  const Interval ahead{0, std::numeric_limits<double>::infinity()};
  const double margin = 0.01;
  int nonempty = 0, looser = 0;
  for (int i = 0; i < 5000; ++i) {
    const auto [a, b] = RandomNearbyPair(rng);
    const Vector3d direction(u(rng), u(rng), u(rng));
    const SweptIntervals bounds = SweptPlaneBounds(a, b, direction, margin, ahead);
    for (const auto& [interval, bound] :
         {std::pair{SweptIntersection(a, b, direction, 0.0, ahead), bounds.exact},
          std::pair{SweptIntersection(a, b, direction, margin, ahead), bounds.within_margin}}) {
      if (interval.empty()) continue;
      ++nonempty;
      ASSERT_FALSE(bound.empty()) << i;
      EXPECT_TRUE(bound.lo <= interval.lo && interval.hi <= bound.hi) << i;
      looser += bound.hi > interval.hi;
    }
  }
  EXPECT_GT(nonempty, 1000);
  EXPECT_GT(looser, 100);  // a bound, not a copy
}

// What a test learns holds while the pair moves less than it says: b is
// turned by an angle up to pi/6 (mostly far less) about a point near its
// centre and shifted, scaled
// so that each corner's motion (of b's, and of a's seen from b) plus the
// hint's lever times the turn stays under its gap, up to 99.9 % of it: the
// pair is then still apart, with and without the hint. Both kinds of gap
// must occur: a face plane's and an edge cross's, whose axis swings as b
// turns.
TEST(TriangleSatTest, HintGapHoldsWhileTheMotionStaysUnderIt) {
  std::mt19937 rng(15);
  std::uniform_real_distribution<double> u(-1, 1), fraction(0, 1);
  int plane_gaps = 0, edge_gaps = 0;
  for (int i = 0; i < 20000; ++i) {
    // Named, not bound: the lambdas below capture them.
    const std::pair<Triangle3d, Triangle3d> pair = RandomNearbyPair(rng);
    const Triangle3d &a = pair.first, &b = pair.second;
    for (double margin : {1e-9, 1e-3, 0.05}) {
      PairHint hint;
      if (TrianglesIntersect(a, TriangleNormal(a), b, TriangleNormal(b), margin, hint) ||
          !(hint.gap_m > 0)) {
        continue;
      }
      // About b's centre: b's corners barely move while its edges swing.
      const Vector3d pivot = (b[0] + b[1] + b[2]) / 3 + 0.1 * Vector3d(u(rng), u(rng), u(rng));
      const Eigen::AngleAxisd turn(std::numbers::pi / 6 * std::pow(fraction(rng), 3),
                                   Vector3d(u(rng), u(rng), u(rng)).normalized());
      const Vector3d shift = Vector3d(u(rng), u(rng), u(rng));
      // b's motion x -> pivot + R (x - pivot) + s * shift, for the scale s
      // that spends `spend` of the gap.
      auto move = [&](double s, const Vector3d& x) -> Vector3d {
        return pivot + turn.toRotationMatrix() * (x - pivot) + s * shift;
      };
      auto unmove = [&](double s, const Vector3d& x) -> Vector3d {
        return pivot + turn.toRotationMatrix().transpose() * (x - s * shift - pivot);
      };
      auto cost = [&](double s) {
        double most = 0;
        for (int k = 0; k < 3; ++k) {
          most = std::max({most, (move(s, b[k]) - b[k]).norm(), (unmove(s, a[k]) - a[k]).norm()});
        }
        return most + hint.lever_m * 2 * std::sin(turn.angle() / 2);
      };
      const double spend = std::min(0.999, fraction(rng) * 1.2);
      if (!(cost(0) < spend * hint.gap_m)) continue;  // the turn alone spends too much
      // The largest shift within the budget, by bisection.
      double lo = 0, hi = 1;
      while (cost(hi) < spend * hint.gap_m) hi *= 2;
      for (int k = 0; k < 60; ++k) {
        const double mid = (lo + hi) / 2;
        (cost(mid) < spend * hint.gap_m ? lo : hi) = mid;
      }
      Triangle3d moved;
      for (int k = 0; k < 3; ++k) moved[k] = move(lo, b[k]);
      PairHint again = hint;
      ASSERT_FALSE(TrianglesIntersect(a, moved, margin)) << "pair " << i << " margin " << margin;
      ASSERT_FALSE(
          TrianglesIntersect(a, TriangleNormal(a), moved, TriangleNormal(moved), margin, again))
          << "pair " << i << " margin " << margin;
      (hint.lever_m > 0 ? edge_gaps : plane_gaps) += 1;
    }
  }
  EXPECT_GT(plane_gaps, 3000);
  EXPECT_GT(edge_gaps, 1000);
}

// A margin makes triangles a small gap apart count, and only within it.
TEST(TriangleSatTest, MarginCountsNearMisses) {
  const Triangle3d a = {Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0, 1, 0)};
  for (double scale : {1e-4, 1.0, 1e4}) {
    SCOPED_TRACE(scale);
    Triangle3d s = a, b = a;
    for (Vector3d& p : s) p *= scale;
    for (Vector3d& p : b) p = p * scale + Vector3d(0, 0, 1e-9 * scale);
    EXPECT_FALSE(TrianglesIntersect(s, b, 0.5e-9 * scale));
    EXPECT_TRUE(TrianglesIntersect(s, b, 2e-9 * scale));
  }
}

// A direction parallel to the separating gap never closes it: the interval
// is empty, and a zero direction gives all t or none.
TEST(TriangleSatTest, SweepParallelToGapIsEmpty) {
  const Triangle3d a = {Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0, 1, 0)};
  Triangle3d b = a;
  for (Vector3d& p : b) p.z() += 1;
  EXPECT_TRUE(SweptIntersection(a, b, Vector3d(1, 0, 0), 0).empty());
  EXPECT_TRUE(SweptIntersection(a, b, Vector3d::Zero(), 0).empty());
  const Interval all = SweptIntersection(a, a, Vector3d::Zero(), 0);
  EXPECT_TRUE(all.Contains(-1e300) && all.Contains(1e300));
  const Interval down = SweptIntersection(a, b, Vector3d(0, 0, -1), 0);
  EXPECT_DOUBLE_EQ(down.lo, 1.0);
  EXPECT_DOUBLE_EQ(down.hi, 1.0);
}

}  // namespace
}  // namespace hs

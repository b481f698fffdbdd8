#include "common/contact/closest_points.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <random>

namespace hs {
namespace {

// Two oracles, one exact and one brute force. Exact: q is the point of a
// convex set S closest to p iff q is in S and (p - q).(x - q) <= 0 for every
// x in S, and since that is linear in x the corners of S suffice. Brute
// force: no point of a fine grid over S is closer than q.

constexpr int kCases = 2000;

Vector3d RandomPoint(std::mt19937& rng, double reach) {
  std::uniform_real_distribution<double> u(-reach, reach);
  return Vector3d(u(rng), u(rng), u(rng));
}

// Barycentric coordinates of q in triangle (a, b, c), least squares.
Vector3d Barycentric(const Vector3d& q, const Vector3d& a, const Vector3d& b, const Vector3d& c) {
  Eigen::Matrix<double, 3, 2> m;
  m << b - a, c - a;
  const Eigen::Vector2d uv = m.colPivHouseholderQr().solve(q - a);
  return Vector3d(1 - uv.sum(), uv[0], uv[1]);
}

// The smallest distance from p to the points of a grid of `n` steps per side
// over triangle (a, b, c).
double GridDistance(const Vector3d& p, const Vector3d& a, const Vector3d& b, const Vector3d& c,
                    int n) {
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; i + j <= n; ++j) {
      const Vector3d x = a + (b - a) * (double(i) / n) + (c - a) * (double(j) / n);
      best = std::min(best, (x - p).norm());
    }
  }
  return best;
}

// On random points and triangles the result lies in the triangle, no corner
// is on the far side of it as seen from p (the exact optimality condition),
// and no grid point of the triangle is closer.
TEST(ClosestPointsTest, PointOnTriangleIsTheNearestPointOfTheTriangle) {
  std::mt19937 rng(11);
  for (int k = 0; k < kCases; ++k) {
    const Vector3d a = RandomPoint(rng, 1), b = RandomPoint(rng, 1), c = RandomPoint(rng, 1);
    const Vector3d p = RandomPoint(rng, 2);
    const Vector3d q = ClosestPointOnTriangle(p, a, b, c);
    const Vector3d w = Barycentric(q, a, b, c);
    EXPECT_GE(w.minCoeff(), -1e-9) << k;
    EXPECT_LT((w[0] * a + w[1] * b + w[2] * c - q).norm(), 1e-9) << k;  // in its plane
    for (const Vector3d& corner : {a, b, c}) EXPECT_LE((p - q).dot(corner - q), 1e-12) << k;
    EXPECT_LE((p - q).norm(), GridDistance(p, a, b, c, 40) + 1e-12) << k;
  }
}

// A point straight above the inside of a triangle drops onto it; one beyond
// a corner's cone of outward directions goes to that corner.
TEST(ClosestPointsTest, PointOnTriangleHandComputedRegions) {
  const Vector3d a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_TRUE(ClosestPointOnTriangle({0.2, 0.3, 5}, a, b, c).isApprox(Vector3d(0.2, 0.3, 0)));
  EXPECT_EQ(ClosestPointOnTriangle({-1, -2, 1}, a, b, c), a);
  EXPECT_EQ(ClosestPointOnTriangle({3, -0.5, 0}, a, b, c), b);
  EXPECT_EQ(ClosestPointOnTriangle({-0.5, 3, -1}, a, b, c), c);
  // Beyond edge bc (x + y = 1): the foot on it.
  EXPECT_TRUE(ClosestPointOnTriangle({1, 1, 0}, a, b, c).isApprox(Vector3d(0.5, 0.5, 0)));
}

// The hull of three points on a line is the segment between the two
// farthest apart: `q` must lie on it with neither end beyond it from p.
void ExpectNearestOnHullSegment(const Vector3d& p, const Vector3d& q, const Vector3d& a,
                                const Vector3d& b, const Vector3d& c) {
  const Vector3d ends[3][2] = {{a, b}, {b, c}, {c, a}};
  const auto* longest = std::max_element(std::begin(ends), std::end(ends), [](auto& x, auto& y) {
    return (x[1] - x[0]).squaredNorm() < (y[1] - y[0]).squaredNorm();
  });
  const Vector3d &s0 = (*longest)[0], &s1 = (*longest)[1];
  EXPECT_NEAR((q - s0).norm() + (q - s1).norm(), (s1 - s0).norm(), 1e-9);  // on it
  EXPECT_LE((p - q).dot(s0 - q), 1e-12);
  EXPECT_LE((p - q).dot(s1 - q), 1e-12);
}

// A zero-area triangle gives the nearest point of its segments: two equal
// corners, three points on a line up to rounding (c = a + u (b - a)), and
// three exactly on one (coordinates in eighths), where p's distances still
// round.
TEST(ClosestPointsTest, PointOnDegenerateTriangleIsTheNearestPointOfItsSegments) {
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> u(-0.5, 1.5);
  std::uniform_int_distribution<int> eighths(-8, 8), steps(-8, 16);
  for (int k = 0; k < 3 * kCases; ++k) {
    SCOPED_TRACE(k);
    Vector3d a = RandomPoint(rng, 1), b = RandomPoint(rng, 1), c = b;
    if (k % 3 == 1) c = a + u(rng) * (b - a);
    if (k % 3 == 2) {
      a = Vector3d(eighths(rng), eighths(rng), eighths(rng)) / 8;
      const Vector3d d(eighths(rng), eighths(rng), 1 + std::abs(eighths(rng)));
      b = a + steps(rng) * d / 8;
      c = a + steps(rng) * d / 8;
    }
    const Vector3d p = RandomPoint(rng, 2);
    ExpectNearestOnHullSegment(p, ClosestPointOnTriangle(p, a, b, c), a, b, c);
  }
}

// On random points and segments the result lies on the segment and neither
// end is on the far side of it as seen from p.
TEST(ClosestPointsTest, PointOnSegmentIsTheNearestPointOfTheSegment) {
  std::mt19937 rng(13);
  for (int k = 0; k < kCases; ++k) {
    const Vector3d a = RandomPoint(rng, 1), b = RandomPoint(rng, 1), p = RandomPoint(rng, 2);
    const Vector3d q = ClosestPointOnSegment(p, a, b);
    EXPECT_NEAR((q - a).norm() + (q - b).norm(), (b - a).norm(), 1e-9) << k;
    EXPECT_LE((p - q).dot(a - q), 1e-12) << k;
    EXPECT_LE((p - q).dot(b - q), 1e-12) << k;
  }
  // A segment of zero length is its one point.
  EXPECT_EQ(ClosestPointOnSegment({1, 2, 3}, {4, 5, 6}, {4, 5, 6}), Vector3d(4, 5, 6));
}

// Checks `r` for segments [p1, q1] and [p2, q2]: parameters in [0, 1] give
// its points, and the pair satisfies the optimality condition of the convex
// problem min |x - y| over both segments, block by block.
void ExpectClosestPair(const SegmentClosest& r, const Vector3d& p1, const Vector3d& q1,
                       const Vector3d& p2, const Vector3d& q2) {
  ASSERT_GE(r.s, 0);
  ASSERT_LE(r.s, 1);
  ASSERT_GE(r.t, 0);
  ASSERT_LE(r.t, 1);
  EXPECT_LT((r.on_first - (p1 + r.s * (q1 - p1))).norm(), 1e-12);
  EXPECT_LT((r.on_second - (p2 + r.t * (q2 - p2))).norm(), 1e-12);
  const Vector3d gap = r.on_first - r.on_second;
  for (const Vector3d& x : {p1, q1}) EXPECT_GE(gap.dot(x - r.on_first), -1e-12);
  for (const Vector3d& y : {p2, q2}) EXPECT_GE((-gap).dot(y - r.on_second), -1e-12);
}

// On random segment pairs the two points are the closest pair, and no pair
// of a grid over both segments is closer.
TEST(ClosestPointsTest, SegmentsGiveTheClosestPair) {
  std::mt19937 rng(14);
  for (int k = 0; k < kCases; ++k) {
    SCOPED_TRACE(k);
    const Vector3d p1 = RandomPoint(rng, 1), q1 = RandomPoint(rng, 1);
    const Vector3d p2 = RandomPoint(rng, 1), q2 = RandomPoint(rng, 1);
    const SegmentClosest r = ClosestPointsOfSegments(p1, q1, p2, q2);
    ExpectClosestPair(r, p1, q1, p2, q2);
    double grid = std::numeric_limits<double>::infinity();
    constexpr int n = 30;
    for (int i = 0; i <= n; ++i) {
      for (int j = 0; j <= n; ++j) {
        grid = std::min(
            grid, (p1 + (q1 - p1) * (double(i) / n) - p2 - (q2 - p2) * (double(j) / n)).norm());
      }
    }
    EXPECT_LE((r.on_first - r.on_second).norm(), grid + 1e-12);
  }
}

// Parallel, collinear and zero-length segments still give a closest pair.
TEST(ClosestPointsTest, SegmentsDegenerateCases) {
  struct Case {
    Vector3d p1, q1, p2, q2;
    double distance;
  };
  const Case cases[] = {
      {{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {2, 1, 0}, 1},           // parallel, overlapping
      {{0, 0, 0}, {1, 0, 0}, {3, 0, 2}, {4, 0, 2}, std::sqrt(8)},  // parallel, apart
      {{0, 0, 0}, {2, 0, 0}, {1, 0, 0}, {3, 0, 0}, 0},             // collinear, overlapping
      {{0, 0, 0}, {0, 0, 0}, {-1, 1, 0}, {1, 1, 0}, 1},            // a point and a segment
      {{-1, 1, 0}, {1, 1, 0}, {0, 0, 0}, {0, 0, 0}, 1},            // a segment and a point
      {{1, 2, 3}, {1, 2, 3}, {1, 2, 5}, {1, 2, 5}, 2},             // two points
  };
  for (const Case& c : cases) {
    const SegmentClosest r = ClosestPointsOfSegments(c.p1, c.q1, c.p2, c.q2);
    ExpectClosestPair(r, c.p1, c.q1, c.p2, c.q2);
    EXPECT_NEAR((r.on_first - r.on_second).norm(), c.distance, 1e-12);
  }
}

}  // namespace
}  // namespace hs

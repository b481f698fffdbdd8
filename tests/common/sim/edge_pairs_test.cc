#include "common/sim/edge_pairs.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <random>

#include "tests/common/sim/random_edges.h"

namespace hs {
namespace {

// An edge from `from` to `to` whose faces' normals sum to `out`.
WorldEdge Edge(const Vector3d& from, const Vector3d& to, const Vector3d& out) {
  return {from, to, out};
}

using testing_edges::DoublesAround;
using testing_edges::FindFlip;
using testing_edges::RandomEdge;
using testing_edges::RandomUnit;
using testing_edges::Shifted;

// The distance of two segments by brute force: the nearest of a grid of
// points on each, an upper bound within a grid step of the true one.
double BruteSegmentDistance(const WorldEdge& p, const WorldEdge& q, int steps) {
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= steps; ++i) {
    const Vector3d x = p.from + (static_cast<double>(i) / steps) * (p.to - p.from);
    for (int j = 0; j <= steps; ++j) {
      const Vector3d y = q.from + (static_cast<double>(j) / steps) * (q.to - q.from);
      best = std::min(best, (x - y).norm());
    }
  }
  return best;
}

TEST(EdgePairPlaneTest, CrossedEdgesGiveTheirCommonNormalAndGap) {
  // The tool's bottom edge along x, 3 mm above the object's top edge along
  // y: the plane is the object's top, the gap 3 mm, at the crossing.
  const WorldEdge tool = Edge({-1, 0, 0.003}, {1, 0, 0.003}, {0, 0, -1});
  const WorldEdge object = Edge({0.2, -1, 0}, {0.2, 1, 0}, {0, 0, 1});
  ConstraintPlane plane;
  ASSERT_TRUE(EdgePairPlane(tool, object, plane));
  EXPECT_NEAR((plane.normal_W - Vector3d(0, 0, 1)).norm(), 0, 1e-15);
  EXPECT_NEAR(plane.gap_m, 0.003, 1e-15);
  EXPECT_NEAR((plane.point_W - Vector3d(0.2, 0, 0)).norm(), 0, 1e-15);
  EXPECT_NEAR((plane.tool_point_W - Vector3d(0.2, 0, 0.003)).norm(), 0, 1e-15);
}

TEST(EdgePairPlaneTest, NoPlaneForParallelEdgesEdgesThatMissOrFacesInTheWay) {
  const WorldEdge object = Edge({0, -1, 0}, {0, 1, 0}, {0, 0, 1});
  ConstraintPlane plane;
  // Parallel: the vertex pairs hold those.
  EXPECT_FALSE(EdgePairPlane(Edge({0, -1, 0.01}, {0, 1, 0.01}, {0, 0, -1}), object, plane));
  // The lines' closest point is off the tool edge.
  EXPECT_FALSE(EdgePairPlane(Edge({0.1, 0, 0.01}, {1, 0, 0.01}, {0, 0, -1}), object, plane));
  // The tool edge's faces face away from the object: its own faces are in
  // the way.
  EXPECT_FALSE(EdgePairPlane(Edge({-1, 0, 0.01}, {1, 0, 0.01}, {0, 0, 1}), object, plane));
}

TEST(SegmentDistanceTest, IsTheBruteForceDistanceOfRandomSegments) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 300; ++trial) {
    const WorldEdge p = RandomEdge(rng, 1), q = RandomEdge(rng, 1);
    const double d = SegmentDistance(p.from, p.to, q.from, q.to);
    const double brute = BruteSegmentDistance(p, q, 400);
    // The brute force is an upper bound off by at most half a step of the
    // longer segment on each.
    EXPECT_LE(d, brute + 1e-12) << trial;
    EXPECT_GE(d, brute - 2 * (2.0 / 400)) << trial;
  }
}

TEST(SegmentDistanceTest, HandlesParallelAndPointSegments) {
  const Vector3d o = Vector3d::Zero(), x = Vector3d::UnitX();
  EXPECT_DOUBLE_EQ(SegmentDistance(o, x, Vector3d(0.5, 2, 0), Vector3d(3, 2, 0)), 2);
  EXPECT_DOUBLE_EQ(SegmentDistance(o, x, Vector3d(2, 0, 0), Vector3d(3, 0, 0)), 1);
  EXPECT_DOUBLE_EQ(SegmentDistance(o, o, Vector3d(0, 3, 4), Vector3d(0, 3, 4)), 5);
  EXPECT_DOUBLE_EQ(SegmentDistance(Vector3d(0.5, 1, 0), Vector3d(0.5, 1, 0), o, x), 1);
}

// The promise the face search rests on: a pair that gives a plane after a
// move within the margin passes EdgePairMayGivePlane before it. Each pair
// is moved by random shifts (and turns about the tool's origin, where the
// move allows them) of at most the margin at the lever, and tested
// exactly there.
TEST(EdgePairMayGivePlaneTest, KeepsEveryPairThatGivesAPlaneAfterAMoveWithinTheMargin) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0, 1);
  constexpr double kRadius = 0.01, kBehind = 1e-8, kMargin = 0.002, kLever = 0.05;
  int planes_after = 0;
  for (int trial = 0; trial < 100000; ++trial) {
    const bool turns = trial % 2 == 1;
    const double turn = turns ? kMargin / kLever : 0;
    const EdgeMove move(kMargin, turn, kRadius, kBehind);
    const WorldEdge tool = RandomEdge(rng, 0.01), object = RandomEdge(rng, 0.01);
    // The move: a shift, and a turn about the tool's origin, whose point at
    // the lever moves by the rest of the margin.
    const double shift_m = kMargin * unit(rng);
    const Vector3d shift = shift_m * RandomUnit(rng);
    const Eigen::AngleAxisd rotation(turns ? (kMargin - shift_m) / kLever * unit(rng) : 0,
                                     RandomUnit(rng));
    auto moved = [&](const Vector3d& p) { return Vector3d(rotation * p + shift); };
    const WorldEdge tool_moved{moved(tool.from), moved(tool.to), rotation * tool.out};
    ConstraintPlane plane;
    if (!EdgePairPlane(tool_moved, object, plane) || plane.gap_m < -kBehind ||
        plane.gap_m > kRadius) {
      continue;
    }
    ++planes_after;
    double apart_m;
    EXPECT_TRUE(
        EdgePairMayGivePlane(tool, LengthsOf(tool), object, LengthsOf(object), move, apart_m))
        << trial;
  }
  EXPECT_GT(planes_after, 500);  // the property met often enough to say something
}

TEST(EdgePairMayGivePlaneTest, WithoutAMarginIsThePlaneTest) {
  std::mt19937 rng(8);
  constexpr double kRadius = 0.01, kBehind = 1e-8;
  const EdgeMove move(0, 0, kRadius, kBehind);
  int planes = 0;
  for (int trial = 0; trial < 50000; ++trial) {
    const WorldEdge tool = RandomEdge(rng, 0.01), object = RandomEdge(rng, 0.01);
    ConstraintPlane plane;
    const bool gives =
        EdgePairPlane(tool, object, plane) && plane.gap_m >= -kBehind && plane.gap_m <= kRadius;
    planes += gives;
    double apart_m;
    EXPECT_EQ(EdgePairMayGivePlane(tool, LengthsOf(tool), object, LengthsOf(object), move, apart_m),
              gives)
        << trial;
  }
  EXPECT_GT(planes, 150);
}

// EdgeLinesMayMeet says no only where EdgePairMayGivePlane does, with and
// without a margin and a turn, and it says no to most random pairs (it is
// the batch's first cut).
TEST(EdgeLinesMayMeetTest, TurnsAwayOnlyPairsThatCannotGiveAPlane) {
  std::mt19937 rng(9);
  for (const double margin : {0.0, 0.002}) {
    for (const double turn : {0.0, 0.04}) {
      const EdgeMove move(margin, turn, 0.01, 1e-8);
      int turned_away = 0, trials = 20000;
      for (int trial = 0; trial < trials; ++trial) {
        const WorldEdge tool = RandomEdge(rng, 0.01), object = RandomEdge(rng, 0.01);
        const EdgeLengths lt = LengthsOf(tool), lo = LengthsOf(object);
        if (EdgeLinesMayMeet(tool.from, tool.to - tool.from, lt.edge_m, object.from,
                             object.to - object.from, lo.edge_m, move)) {
          continue;
        }
        ++turned_away;
        double apart_m;
        EXPECT_FALSE(EdgePairMayGivePlane(tool, lt, object, lo, move, apart_m))
            << "margin " << margin << " turn " << turn << " trial " << trial;
      }
      EXPECT_GT(turned_away, trials / 4) << "margin " << margin << " turn " << turn;
    }
  }
}

// Without a margin the closest points may fall past an edge's end by at
// least twice EdgePairPlane's ends (1e-9 of the edge), whatever the edges'
// lengths: room for the two tests' rounding.
TEST(EdgeLinesMayMeetTest, KeepsClosestPointsWithinTwiceThePlanesEnds) {
  const EdgeMove move(0, 0, 0.01, 1e-8);
  // The tool edge along x (length 1), a short object edge (0.1) across it
  // 1.5e-9 before its start: a = -1.5e-9.
  const Vector3d t_from(0, 0, 0.001), u(1, 0, 0), v(0, 0.1, 0);
  EXPECT_TRUE(EdgeLinesMayMeet(t_from, u, 1, Vector3d(-1.5e-9, -0.05, 0), v, 0.1, move));
  EXPECT_FALSE(EdgeLinesMayMeet(t_from, u, 1, Vector3d(-3e-9, -0.05, 0), v, 0.1, move));
  // And past its end.
  EXPECT_TRUE(EdgeLinesMayMeet(t_from, u, 1, Vector3d(1 + 1.5e-9, -0.05, 0), v, 0.1, move));
  EXPECT_FALSE(EdgeLinesMayMeet(t_from, u, 1, Vector3d(1 + 3e-9, -0.05, 0), v, 0.1, move));
}

// Edge pairs at the point where EdgeLinesMayMeet's answer flips (found by
// bisection along a random shift of the object edge) and where
// EdgePairMayGivePlane's does, and a few doubles either side: the first
// says no only where the second does.
TEST(EdgeLinesMayMeetTest, TurnsAwayOnlyPairsThatCannotGiveAPlaneWhereEitherAnswerFlips) {
  std::mt19937 rng(10);
  int flips = 0;
  for (const double margin : {0.0, 0.002}) {
    for (const double turn : {0.0, 0.04}) {
      const EdgeMove move(margin, turn, 0.01, 1e-8);
      for (int trial = 0; trial < 400; ++trial) {
        const WorldEdge tool = RandomEdge(rng, 0.01), object = RandomEdge(rng, 0.01);
        const Vector3d direction = RandomUnit(rng);
        const EdgeLengths lt = LengthsOf(tool);
        // Each shift's edge with its own vector and length, as a search
        // places it.
        auto lines = [&](double s) {
          const WorldEdge o = Shifted(object, s, direction);
          return EdgeLinesMayMeet(tool.from, tool.to - tool.from, lt.edge_m, o.from, o.to - o.from,
                                  LengthsOf(o).edge_m, move);
        };
        auto full = [&](double s) {
          const WorldEdge o = Shifted(object, s, direction);
          double apart_m;
          return EdgePairMayGivePlane(tool, lt, o, LengthsOf(o), move, apart_m);
        };
        for (const auto& answer :
             {std::function<bool(double)>(lines), std::function<bool(double)>(full)}) {
          double lo, hi;
          if (!FindFlip(answer, lo, hi)) continue;
          ++flips;
          for (const double s : DoublesAround(lo)) {
            if (!lines(s)) {
              EXPECT_FALSE(full(s)) << "trial " << trial << " shift " << s;
            }
          }
        }
      }
    }
  }
  EXPECT_GT(flips, 200);
}

TEST(EdgeLinesMayMeetTest, LeavesNearParallelAndNonFiniteEdgesToTheFullTest) {
  const EdgeMove move(0.002, 0, 0.01, 1e-8);
  const Vector3d x = Vector3d::UnitX();
  // Parallel and 1e-7 off parallel, far past each other's ends.
  EXPECT_TRUE(EdgeLinesMayMeet(Vector3d(5, 0, 0), x, 1, Vector3d::Zero(), x, 1, move));
  EXPECT_TRUE(
      EdgeLinesMayMeet(Vector3d(5, 0, 0), x, 1, Vector3d::Zero(), Vector3d(1, 1e-7, 0), 1, move));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(
      EdgeLinesMayMeet(Vector3d(nan, 0, 0), Vector3d::UnitY(), 1, Vector3d::Zero(), x, 1, move));
  // Crossed, but far past the object edge's end: turned away.
  EXPECT_FALSE(
      EdgeLinesMayMeet(Vector3d(5, -1, 0.001), Vector3d(0, 2, 0), 2, Vector3d::Zero(), x, 1, move));
}

}  // namespace
}  // namespace hs

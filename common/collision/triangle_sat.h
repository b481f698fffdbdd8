#pragma once
// Triangle-triangle tests by the separating axis theorem (SAT): the lean
// leaf test of the BVH traversal, and the exact sweep interval of the 3D
// contact method (docs/algorithm.md).
//
// Axes: both face normals, the 9 cross products of edge pairs, and the 6
// in-plane edge normals (face normal x edge), which separate coplanar
// triangles. Any axis is a sound separation witness, and these 17 are
// complete for two non-degenerate triangles, so the tests are exact up to
// rounding. Near-zero axes (parallel edges, degenerate faces) are skipped.

#include <array>
#include <cstdint>
#include <limits>

#include "common/core/types.h"

namespace hs {

using Triangle3d = std::array<Vector3d, 3>;
/// A face by its three corners, read where they are kept (a model's
/// vertices, or vertices placed once per query), not copied.
using TriangleCorners = std::array<const Vector3d*, 3>;

/// A closed interval of a real parameter; empty when lo > hi.
struct Interval {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  bool empty() const { return lo > hi; }
  bool Contains(double t) const { return lo <= t && t <= hi; }
  /// True when the interval shares a point with [from, to].
  bool Overlaps(double from, double to) const { return lo <= to && from <= hi && !empty(); }
};

/// Every real t.
inline constexpr Interval kWholeLine{-std::numeric_limits<double>::infinity(),
                                     std::numeric_limits<double>::infinity()};

/// True when triangles `a` and `b` (same frame) intersect or are closer than
/// `margin` (metres, >= 0) along every axis: touching counts as intersecting.
bool TrianglesIntersect(const Triangle3d& a, const Triangle3d& b, double margin);

/// The normal of `t`, (t[1] - t[0]) x (t[2] - t[1]), unnormalised.
Vector3d TriangleNormal(const Triangle3d& t);

/// TrianglesIntersect with each triangle's TriangleNormal given, for callers
/// that test one triangle against many.
bool TrianglesIntersect(const Triangle3d& a, const Vector3d& normal_a, const Triangle3d& b,
                        const Vector3d& normal_b, double margin);

/// What a test of a pair told about its next test, as the pair moves.
struct PairHint {
  /// The edge cross that separated the two (3 i + j: edge i of `a`, from
  /// corner i to i + 1, and edge j of `b`), or -1.
  int edge_pair = -1;
  /// When a face's plane or the edge cross separated them: how far beyond
  /// the margin, metres; else 0. They stay apart, and the same test says
  /// so, while each moves less than gap_m - lever_m * (the angle through
  /// which one turns relative to the other), up to rounding.
  double gap_m = 0;
  /// 0 for a face plane, which turns with its face (the distance from it
  /// only changes as the other face moves); for an edge cross, whose axis
  /// swings as the edges turn, the most the gap along it changes per
  /// radian of turn: 2 |e_a| |e_b| / |e_a x e_b| times the farthest two
  /// corners of the pair lie apart.
  double lever_m = 0;
};

/// Relative to the triangles' size, what rounding cannot reach: the fast
/// crossing test (Moller's interval test, inside TrianglesIntersect)
/// answers only when every quantity it compares stands clear of zero by
/// this much, and leaves every other pair to the SAT.
inline constexpr double kClearlyRelative = 1e-9;

/// What TrianglesIntersect's first tests (each face's plane, then the fast
/// crossing test) say of a pair, where they answer alone.
struct QuickTriangleTest {
  enum class Answer : uint8_t { kUnknown, kMeet, kApart, kEdgesApart };
  Answer answer = Answer::kUnknown;
  /// kEdgesApart: the edge cross that keeps them apart (PairHint's
  /// numbering); else -1.
  int8_t edge_pair = -1;
  /// kApart: how far beyond the margin the face's plane keeps them.
  double gap_m = 0;
};

/// kApart: a face's plane keeps the other face beyond `margin`;
/// TrianglesIntersect is false, and with a hint it sets gap_m to this
/// test's and lever_m to 0, and leaves edge_pair as it was. kMeet: neither
/// plane does and the fast crossing test finds a clear common point;
/// TrianglesIntersect is true, and with a hint it leaves edge_pair as it
/// was and sets gap_m and lever_m to 0 (no axis can separate a clear common
/// point). kEdgesApart, only with `edge_cross`: neither plane does, and an
/// edge cross keeps them beyond `margin`: where the two cross the line
/// where the planes meet apart, the cross of the edges that give the
/// facing ends; where a face does not straddle the other's plane clearly
/// (or the planes are parallel), the first of the nine that does
/// (ForEachAxis's order); TrianglesIntersect is false. kUnknown: the full
/// test decides. The oracle of the batched test (face_test_batch.h).
QuickTriangleTest QuickTrianglesTest(const Triangle3d& a, const Vector3d& normal_a,
                                     const Triangle3d& b, const Vector3d& normal_b, double margin,
                                     bool edge_cross);

/// The same answer, for callers that test a pair again and again as it
/// moves: the edge cross of `hint` is tried right after the face planes,
/// and when it still separates the pair the whole test is skipped (which
/// gives the same answer: see the definition). `hint` is then set from
/// this test.
bool TrianglesIntersect(const Triangle3d& a, const Vector3d& normal_a, const Triangle3d& b,
                        const Vector3d& normal_b, double margin, PairHint& hint);

/// Whether the cross of edge i of `a` and edge j of `b` (each from corner
/// i to i + 1), built and projected as the full test builds it, keeps them
/// beyond `margin`; `hint` gets that axis's gap and lever (PairHint), 0
/// when it does not separate them. With a hint of this edge pair,
/// TrianglesIntersect tries it right after the planes. The oracle of the
/// batched test (face_test_batch.h).
bool EdgeCrossSeparates(const Triangle3d& a, const Triangle3d& b, int i, int j, double margin,
                        PairHint& hint);

/// The set of t for which `a` translated by -t * `direction` intersects `b`
/// (within `margin`; a negative margin asks for an overlap deeper than
/// -margin along every axis). Always one closed interval (a line through the convex
/// Minkowski difference); unbounded ends are +-inf. `direction` need not be
/// unit: t is in units of its length. With a `within`, the result is cut to
/// it, and the test stops as soon as the cut is empty: callers that care
/// about part of the line only should say which.
Interval SweptIntersection(const Triangle3d& a, const Triangle3d& b, const Vector3d& direction,
                           double margin, Interval within = kWholeLine);

/// SweptIntersection with each triangle's TriangleNormal given.
Interval SweptIntersection(const Triangle3d& a, const Vector3d& normal_a, const Triangle3d& b,
                           const Vector3d& normal_b, const Vector3d& direction, double margin,
                           Interval within);

/// Whether the cut of `within` along the two face normals alone (the
/// bound SweptPlaneBounds gives at `margin`) is not empty: where the
/// planes rule a pair out, so would every axis.
bool SweptPlanesMeet(const Triangle3d& a, const Vector3d& normal_a, const Triangle3d& b,
                     const Vector3d& normal_b, const Vector3d& direction, double margin,
                     Interval within);

/// Below this (relative to the product of the lengths that formed it) a
/// separating axis is a rounding artefact of parallel edges or a flat face,
/// and is skipped.
inline constexpr double kAxisRelativeFloor = 1e-12;

/// Sweep intervals of one pair at zero margin and at a margin.
struct SweptIntervals {
  Interval exact;          // margin 0
  Interval within_margin;  // the margin given; holds `exact`
};

/// Cheap bounds of SweptIntersection(a, b, direction, m, within) at m = 0
/// and m = `margin`, in one pass: the same cuts along the two face normals
/// alone, at a fifth of the axes. Where a bound misses some t, so does its
/// interval.
SweptIntervals SweptPlaneBounds(const Triangle3d& a, const Triangle3d& b, const Vector3d& direction,
                                double margin, Interval within);

}  // namespace hs

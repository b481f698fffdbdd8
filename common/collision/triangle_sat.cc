#include "common/collision/triangle_sat.h"

#include <algorithm>
#include <cmath>
#include <optional>

namespace hs {
namespace {

// Above this sine of the angle between two faces' planes, the in-plane
// edge normals are not needed (ForEachAxis); far above rounding, far below
// any angle between faces of a real mesh that matters.
constexpr double kPlanesCrossSin = 1e-6;

// A triangle's extent along an axis.
struct Extent {
  double lo, hi;
};

Extent ProjectTwo(const Vector3d& axis, const Vector3d& p, const Vector3d& q) {
  const double x = axis.dot(p), y = axis.dot(q);
  return {std::min(x, y), std::max(x, y)};
}

Extent ProjectThree(const Vector3d& axis, const Triangle3d& t) {
  const double x = axis.dot(t[0]), y = axis.dot(t[1]), z = axis.dot(t[2]);
  return {std::min(std::min(x, y), z), std::max(std::max(x, y), z)};
}

// Whether `axis`, formed from vectors whose squared lengths multiply to
// `scale_sq`, is long enough to trust; `norm_sq` gets its squared length.
bool UsableAxis(const Vector3d& axis, double scale_sq, double& norm_sq) {
  norm_sq = axis.squaredNorm();
  return norm_sq > kAxisRelativeFloor * kAxisRelativeFloor * scale_sq && norm_sq != 0;
}

// The SAT axis of edge i of `a` crossed with edge j of `b` (ea, eb, of
// squared lengths la, lb; edge i from corner i to i + 1): calls
// visit(axis, squared_axis_norm, extent_of_a, extent_of_b) and returns its
// answer, or true when the axis is too short to trust. An axis normal to an
// edge sees both ends of it at one point, so one of them is projected.
template <typename Visit>
bool VisitEdgeCross(const Triangle3d& a, const Vector3d& ea, double la, int i, const Triangle3d& b,
                    const Vector3d& eb, double lb, int j, Visit&& visit) {
  const Vector3d axis = ea.cross(eb);
  double norm_sq;
  if (!UsableAxis(axis, la * lb, norm_sq)) return true;
  return visit(axis, norm_sq, ProjectTwo(axis, a[i], a[(i + 2) % 3]),
               ProjectTwo(axis, b[j], b[(j + 2) % 3]));
}

// Calls visit(axis, squared_axis_norm, extent_of_a, extent_of_b) for every
// usable SAT axis of the pair; stops early and returns false when visit
// returns false. `na` and `nb` are the face normals (TriangleNormal). An
// axis normal to an edge sees both ends of that edge at one point, so one
// of them is projected, not both (a quarter fewer dot products). With
// kFaceNormalsOnly, the face normals only.
template <bool kFaceNormalsOnly = false, typename Visit>
bool ForEachAxis(const Triangle3d& a, const Vector3d& na, const Triangle3d& b, const Vector3d& nb,
                 Visit&& visit) {
  const std::array<Vector3d, 3> ea = {a[1] - a[0], a[2] - a[1], a[0] - a[2]};
  const std::array<Vector3d, 3> eb = {b[1] - b[0], b[2] - b[1], b[0] - b[2]};
  const double la[3] = {ea[0].squaredNorm(), ea[1].squaredNorm(), ea[2].squaredNorm()};
  const double lb[3] = {eb[0].squaredNorm(), eb[1].squaredNorm(), eb[2].squaredNorm()};
  const double la_max = std::max(std::max(la[0], la[1]), la[2]);
  const double lb_max = std::max(std::max(lb[0], lb[1]), lb[2]);
  double norm_sq;
  if (UsableAxis(na, la_max * la_max, norm_sq)) {
    const double at = na.dot(a[0]);
    if (!visit(na, norm_sq, Extent{at, at}, ProjectThree(na, b))) return false;
  }
  if (UsableAxis(nb, lb_max * lb_max, norm_sq)) {
    const double at = nb.dot(b[0]);
    if (!visit(nb, norm_sq, ProjectThree(nb, a), Extent{at, at})) return false;
  }
  if constexpr (kFaceNormalsOnly) return true;
  // Edge i joins corners i and i + 1; corner i + 2 is off it.
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (!VisitEdgeCross(a, ea[i], la[i], i, b, eb[j], lb[j], j, visit)) return false;
    }
  }
  // The in-plane edge normals separate triangles of (nearly) parallel
  // planes only: where the planes cross, the two face normals and the nine
  // edge crosses are the face normals of the Minkowski difference, so they
  // decide alone, and the other six are implied by them.
  const double cross_sq = na.cross(nb).squaredNorm();
  if (cross_sq > kPlanesCrossSin * kPlanesCrossSin * na.squaredNorm() * nb.squaredNorm()) {
    return true;
  }
  for (int i = 0; i < 3; ++i) {
    const Vector3d axis_a = na.cross(ea[i]);
    if (UsableAxis(axis_a, la_max * la_max * la[i], norm_sq) &&
        !visit(axis_a, norm_sq, ProjectTwo(axis_a, a[i], a[(i + 2) % 3]),
               ProjectThree(axis_a, b))) {
      return false;
    }
    const Vector3d axis_b = nb.cross(eb[i]);
    if (UsableAxis(axis_b, lb_max * lb_max * lb[i], norm_sq) &&
        !visit(axis_b, norm_sq, ProjectThree(axis_b, a),
               ProjectTwo(axis_b, b[i], b[(i + 2) % 3]))) {
      return false;
    }
  }
  return true;
}

// True when the gap between [a_lo, a_hi] and [b_lo, b_hi] along an axis of
// squared length `norm_sq` exceeds `margin` (in metres, so scaled by the
// axis length); squares avoid a square root per axis.
bool SeparatedAlong(double a_lo, double a_hi, double b_lo, double b_hi, double norm_sq,
                    double margin) {
  const double gap = std::max(a_lo - b_hi, b_lo - a_hi);
  return gap > 0 && gap * gap > margin * margin * norm_sq;
}

// Signed distances (times |n|) of the corners of `t` from the plane through
// `origin` with normal `n`.
std::array<double, 3> PlaneDistances(const Triangle3d& t, const Vector3d& origin,
                                     const Vector3d& n) {
  return {n.dot(t[0] - origin), n.dot(t[1] - origin), n.dot(t[2] - origin)};
}

// Whether all corners lie beyond `margin` on one side of a plane with normal
// `n`, given their distances `d` from it: the cheap first test of the leaf,
// which rejects most candidate pairs before the full axis set is built.
bool BeyondPlane(const std::array<double, 3>& d, const Vector3d& n, double margin) {
  const double norm_sq = n.squaredNorm();
  if (norm_sq == 0) return false;
  const double lo = std::min(std::min(d[0], d[1]), d[2]), hi = std::max(std::max(d[0], d[1]), d[2]);
  return SeparatedAlong(lo, hi, 0.0, 0.0, norm_sq, margin);
}

// How far beyond `margin` corners at distances `d` (BeyondPlane's) are.
double PlaneGap(const std::array<double, 3>& d, const Vector3d& n, double margin) {
  const double lo = std::min(std::min(d[0], d[1]), d[2]), hi = std::max(std::max(d[0], d[1]), d[2]);
  return std::max(lo, -hi) / n.norm() - margin;
}

// Where a triangle crosses the other's plane, along the planes' common
// line: an interval of p.dot(line), with the triangle's edge that gives
// each end (as the corner it leaves from and the direction it runs).
struct LineCrossing {
  Extent on_line;
  Vector3d lo_edge, hi_edge;
  int lo_index, hi_index;  // those edges in ForEachAxis's numbering, up to sign
};

// Where `t` crosses the other triangle's plane, given its corners'
// distances `d` from that plane; none unless every corner stands clear of
// the plane (by more than sqrt(`clear_sq`)) and they are not all on one
// side.
std::optional<LineCrossing> CrossingOnLine(const Triangle3d& t, const std::array<double, 3>& d,
                                           double clear_sq, const Vector3d& line,
                                           const Vector3d& origin) {
  // All three compares, with no branch between them.
  const int clear = static_cast<int>(d[0] * d[0] > clear_sq) &
                    static_cast<int>(d[1] * d[1] > clear_sq) &
                    static_cast<int>(d[2] * d[2] > clear_sq);
  if (clear == 0) return std::nullopt;
  // The corner alone on its side, and the other two, in turn after it.
  const bool above[3] = {d[0] > 0, d[1] > 0, d[2] > 0};
  if (above[0] == above[1] && above[1] == above[2]) return std::nullopt;
  const int lone = above[0] == above[1] ? 2 : above[0] == above[2] ? 1 : 0;
  const int next = lone == 2 ? 0 : lone + 1, last = lone == 0 ? 2 : lone - 1;
  const double at_lone = line.dot(t[lone] - origin);
  const double at_next = line.dot(t[next] - origin), at_last = line.dot(t[last] - origin);
  const double end_next = at_next + (at_lone - at_next) * d[next] / (d[next] - d[lone]);
  const double end_last = at_last + (at_lone - at_last) * d[last] / (d[last] - d[lone]);
  // Edge `lone` runs from corner lone to next; edge `last` from last to lone.
  const Vector3d edge_next = t[next] - t[lone], edge_last = t[last] - t[lone];
  if (end_next <= end_last) {
    return LineCrossing{{end_next, end_last}, edge_next, edge_last, lone, last};
  }
  return LineCrossing{{end_last, end_next}, edge_last, edge_next, last, lone};
}

// kNone: no crossings to compare (a face does not straddle the other's
// plane clearly, or the planes are parallel); kUnknown: they do not decide.
enum class Crossing { kYes, kApart, kUnknown, kNone };

// A fast answer for triangles that straddle each other's planes (Moller's
// interval test): the two segments where they cut the planes' common line
// lie inside both triangles, so a clear overlap is a common point (kYes).
// When the segments are apart, the edges that give their facing ends
// usually cross into the separating axis: kApart when it separates the
// triangles by more than `margin`. That axis is one of the SAT's nine edge
// crosses (up to sign), projected the same way, so kApart is the SAT's own
// answer. Anything else is left to the SAT.
Crossing CrossingTest(const Triangle3d& a, const Vector3d& na, const std::array<double, 3>& da,
                      const Triangle3d& b, const Vector3d& nb, const std::array<double, 3>& db,
                      double margin, int& edge_pair) {
  // The pair's size, squared: five times the sum of the squared lengths
  // of the four edges from corner 0 and the gap between the corners 0,
  // at least the square of the sum of those lengths. Squared thresholds
  // throughout: no square root on the fast path.
  const double size_sq =
      5 * ((a[0] - b[0]).squaredNorm() + (a[1] - a[0]).squaredNorm() + (a[2] - a[0]).squaredNorm() +
           (b[1] - b[0]).squaredNorm() + (b[2] - b[0]).squaredNorm());
  const double clear_sq = kClearlyRelative * kClearlyRelative * size_sq;
  const Vector3d line = na.cross(nb);
  const double line_sq = line.squaredNorm();
  if (!(line_sq > 0)) return Crossing::kNone;
  const std::optional<LineCrossing> on_a =
      CrossingOnLine(a, da, clear_sq * nb.squaredNorm(), line, b[0]);
  if (!on_a) return Crossing::kNone;
  const std::optional<LineCrossing> on_b =
      CrossingOnLine(b, db, clear_sq * na.squaredNorm(), line, b[0]);
  if (!on_b) return Crossing::kNone;
  const double overlap =
      std::min(on_a->on_line.hi, on_b->on_line.hi) - std::max(on_a->on_line.lo, on_b->on_line.lo);
  if (overlap > 0 && overlap * overlap > clear_sq * line_sq) return Crossing::kYes;
  if (overlap >= 0) return Crossing::kUnknown;
  const bool a_first = on_a->on_line.hi < on_b->on_line.lo;
  const Vector3d& edge_a = a_first ? on_a->hi_edge : on_a->lo_edge;
  const Vector3d& edge_b = a_first ? on_b->lo_edge : on_b->hi_edge;
  edge_pair =
      3 * (a_first ? on_a->hi_index : on_a->lo_index) + (a_first ? on_b->lo_index : on_b->hi_index);
  const Vector3d axis = edge_a.cross(edge_b);
  const double axis_sq = axis.squaredNorm();
  // Nearly parallel edges give a rounding artefact, as in ForEachAxis.
  if (!(axis_sq >
        kAxisRelativeFloor * kAxisRelativeFloor * (edge_a.squaredNorm() * edge_b.squaredNorm()))) {
    return Crossing::kUnknown;
  }
  const Extent ea = ProjectThree(axis, a), eb = ProjectThree(axis, b);
  return SeparatedAlong(ea.lo, ea.hi, eb.lo, eb.hi, axis_sq, margin) ? Crossing::kApart
                                                                     : Crossing::kUnknown;
}

// Cuts each of `intervals` to the t for which `a` translated by -t *
// `direction` meets `b` within the matching one of `margins`, in one pass
// over the axes (the face normals only, with kFaceNormalsOnly). The margins
// fall from first to last, so the first interval holds the others, and the
// pass stops once it is empty.
template <bool kFaceNormalsOnly, size_t N>
void CutToSweep(const Triangle3d& a, const Vector3d& normal_a, const Triangle3d& b,
                const Vector3d& normal_b, const Vector3d& direction,
                const std::array<double, N>& margins, std::array<Interval, N>& intervals) {
  ForEachAxis<kFaceNormalsOnly>(
      a, normal_a, b, normal_b,
      [&](const Vector3d& axis, double norm_sq, const Extent& ea, const Extent& eb) {
        // Along the axis, a(t) spans [ea.lo - t*s, ea.hi - t*s] with
        // s = axis.D. They overlap while ea.lo - t*s <= eb.hi + slack
        // and eb.lo <= ea.hi - t*s + slack.
        const double s = axis.dot(direction);
        const double inverse = s != 0 ? 1 / s : 0.0;
        const double length = margins[0] != 0 ? std::sqrt(norm_sq) : 0.0;
        for (size_t k = 0; k < N; ++k) {
          Interval& result = intervals[k];
          const double slack = margins[k] * length;
          const double low_gap = ea.lo - eb.hi - slack;   // need t*s >= low_gap
          const double high_gap = ea.hi - eb.lo + slack;  // need t*s <= high_gap
          if (s == 0) {
            if (low_gap > 0 || high_gap < 0) result = Interval{};
          } else {
            const double from_low = low_gap * inverse, from_high = high_gap * inverse;
            result.lo = std::max(result.lo, s > 0 ? from_low : from_high);
            result.hi = std::min(result.hi, s > 0 ? from_high : from_low);
          }
        }
        return !intervals[0].empty();
      });
}

// TrianglesIntersect; with kLearn, the edge cross of `hint` is tried after
// the face planes, and `hint` is set from this test.
template <bool kLearn>
bool Intersect(const Triangle3d& a, const Vector3d& normal_a, const Triangle3d& b,
               const Vector3d& normal_b, double margin, PairHint* hint) {
  if constexpr (kLearn) hint->gap_m = hint->lever_m = 0;
  const std::array<double, 3> db = PlaneDistances(b, a[0], normal_a);
  if (BeyondPlane(db, normal_a, margin)) {
    if constexpr (kLearn) hint->gap_m = PlaneGap(db, normal_a, margin);
    return false;
  }
  const std::array<double, 3> da = PlaneDistances(a, b[0], normal_b);
  if (BeyondPlane(da, normal_b, margin)) {
    if constexpr (kLearn) hint->gap_m = PlaneGap(da, normal_b, margin);
    return false;
  }
  int unused = -1;
  int& edge_pair = kLearn ? hint->edge_pair : unused;
  // A separating edge cross makes every path below answer false: the
  // crossing test's kYes needs a clear common point, which no axis can
  // separate, and ForEachAxis visits that axis, built the same way.
  if (kLearn && edge_pair >= 0 &&
      EdgeCrossSeparates(a, b, edge_pair / 3, edge_pair % 3, margin, *hint)) {
    return false;
  }
  const Crossing crossing = CrossingTest(a, normal_a, da, b, normal_b, db, margin, edge_pair);
  if (crossing == Crossing::kApart && kLearn) {  // its gap along ForEachAxis's axis
    EdgeCrossSeparates(a, b, edge_pair / 3, edge_pair % 3, margin, *hint);
  }
  if (crossing == Crossing::kYes || crossing == Crossing::kApart) {
    return crossing == Crossing::kYes;
  }
  const bool meet =
      ForEachAxis(a, normal_a, b, normal_b,
                  [&](const Vector3d&, double norm_sq, const Extent& ea, const Extent& eb) {
                    return !SeparatedAlong(ea.lo, ea.hi, eb.lo, eb.hi, norm_sq, margin);
                  });
  if (kLearn && !meet) {  // which edge cross separates them, if one does
    edge_pair = -1;
    for (int k = 0; k < 9 && edge_pair < 0; ++k) {
      if (EdgeCrossSeparates(a, b, k / 3, k % 3, margin, *hint)) edge_pair = k;
    }
  }
  return meet;
}

}  // namespace

// Built and projected by ForEachAxis's own VisitEdgeCross: when it
// separates the pair, ForEachAxis finds it too.
bool EdgeCrossSeparates(const Triangle3d& a, const Triangle3d& b, int i, int j, double margin,
                        PairHint& hint) {
  const Vector3d ea = a[(i + 1) % 3] - a[i], eb = b[(j + 1) % 3] - b[j];
  const double la = ea.squaredNorm(), lb = eb.squaredNorm();
  hint.gap_m = hint.lever_m = 0;
  return !VisitEdgeCross(
      a, ea, la, i, b, eb, lb, j,
      [&](const Vector3d&, double norm_sq, const Extent& pa, const Extent& pb) {
        if (!SeparatedAlong(pa.lo, pa.hi, pb.lo, pb.hi, norm_sq, margin)) return true;
        // Turned by an angle u, e_a x e_b moves by at most |e_a| |e_b| u,
        // the unit axis by twice that over |e_a x e_b|, and the gap along
        // it by that times how far apart two corners lie. The axis stays
        // over half its length, so usable, while the gap lasts: below
        // four times the floor, none is kept.
        const double floor_sq = kAxisRelativeFloor * kAxisRelativeFloor * la * lb;
        if (!(norm_sq > 4 * floor_sq * (1 + 1e-6))) return false;
        const Vector3d lo =
            a[0].cwiseMin(a[1]).cwiseMin(a[2]).cwiseMin(b[0]).cwiseMin(b[1]).cwiseMin(b[2]);
        const Vector3d hi =
            a[0].cwiseMax(a[1]).cwiseMax(a[2]).cwiseMax(b[0]).cwiseMax(b[1]).cwiseMax(b[2]);
        const double length = std::sqrt(norm_sq);
        hint.gap_m = std::max(0.0, std::max(pa.lo - pb.hi, pb.lo - pa.hi) / length - margin);
        hint.lever_m = 2 * std::sqrt(la * lb) / length * (hi - lo).norm();
        return false;
      });
}

QuickTriangleTest QuickTrianglesTest(const Triangle3d& a, const Vector3d& normal_a,
                                     const Triangle3d& b, const Vector3d& normal_b, double margin,
                                     bool edge_cross) {
  using Answer = QuickTriangleTest::Answer;
  const std::array<double, 3> db = PlaneDistances(b, a[0], normal_a);
  if (BeyondPlane(db, normal_a, margin)) {
    return {.answer = Answer::kApart, .gap_m = PlaneGap(db, normal_a, margin)};
  }
  const std::array<double, 3> da = PlaneDistances(a, b[0], normal_b);
  if (BeyondPlane(da, normal_b, margin)) {
    return {.answer = Answer::kApart, .gap_m = PlaneGap(da, normal_b, margin)};
  }
  int edge_pair = -1;
  switch (CrossingTest(a, normal_a, da, b, normal_b, db, margin, edge_pair)) {
    case Crossing::kYes:
      return {.answer = Answer::kMeet};
    case Crossing::kApart:
      if (!edge_cross) return {};
      return {.answer = Answer::kEdgesApart, .edge_pair = static_cast<int8_t>(edge_pair)};
    case Crossing::kUnknown:
      return {};
    case Crossing::kNone:
      break;
  }
  if (!edge_cross) return {};
  // Faces with no crossing to compare (a face within the margin of the
  // other's plane, on one side of it: lying on the other face, or beside
  // it) are mostly kept apart by one of the nine edge crosses, the SAT's
  // own axes.
  PairHint unused;
  for (int k = 0; k < 9; ++k) {
    if (EdgeCrossSeparates(a, b, k / 3, k % 3, margin, unused)) {
      return {.answer = Answer::kEdgesApart, .edge_pair = static_cast<int8_t>(k)};
    }
  }
  return {};
}

Vector3d TriangleNormal(const Triangle3d& t) { return (t[1] - t[0]).cross(t[2] - t[1]); }

bool TrianglesIntersect(const Triangle3d& a, const Triangle3d& b, double margin) {
  return TrianglesIntersect(a, TriangleNormal(a), b, TriangleNormal(b), margin);
}

bool TrianglesIntersect(const Triangle3d& a, const Vector3d& normal_a, const Triangle3d& b,
                        const Vector3d& normal_b, double margin) {
  return Intersect<false>(a, normal_a, b, normal_b, margin, nullptr);
}

bool TrianglesIntersect(const Triangle3d& a, const Vector3d& normal_a, const Triangle3d& b,
                        const Vector3d& normal_b, double margin, PairHint& hint) {
  return Intersect<true>(a, normal_a, b, normal_b, margin, &hint);
}

Interval SweptIntersection(const Triangle3d& a, const Triangle3d& b, const Vector3d& direction,
                           double margin, Interval within) {
  return SweptIntersection(a, TriangleNormal(a), b, TriangleNormal(b), direction, margin, within);
}

Interval SweptIntersection(const Triangle3d& a, const Vector3d& normal_a, const Triangle3d& b,
                           const Vector3d& normal_b, const Vector3d& direction, double margin,
                           Interval within) {
  std::array<Interval, 1> result = {within};
  CutToSweep<false>(a, normal_a, b, normal_b, direction, {margin}, result);
  return result[0];
}

bool SweptPlanesMeet(const Triangle3d& a, const Vector3d& normal_a, const Triangle3d& b,
                     const Vector3d& normal_b, const Vector3d& direction, double margin,
                     Interval within) {
  std::array<Interval, 1> result = {within};
  CutToSweep<true>(a, normal_a, b, normal_b, direction, {margin}, result);
  return !result[0].empty();
}

SweptIntervals SweptPlaneBounds(const Triangle3d& a, const Triangle3d& b, const Vector3d& direction,
                                double margin, Interval within) {
  std::array<Interval, 2> result = {within, within};
  CutToSweep<true>(a, TriangleNormal(a), b, TriangleNormal(b), direction, {margin, 0.0}, result);
  return {.exact = result[1], .within_margin = result[0]};
}

}  // namespace hs

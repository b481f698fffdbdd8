#include "common/collision/triangle_sat.h"

#include <algorithm>
#include <cmath>
#include <optional>

namespace hs {
namespace {

// Below this (relative to the product of the lengths that formed it) an axis
// is a rounding artefact of parallel edges or a flat face, and is skipped.
constexpr double kAxisRelativeFloor = 1e-12;

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

// Calls visit(axis, squared_axis_norm, extent_of_a, extent_of_b) for every
// usable SAT axis of the pair; stops early and returns false when visit
// returns false. `na` and `nb` are the face normals (TriangleNormal). An
// axis normal to an edge sees both ends of that edge at one point, so one
// of them is projected, not both (a quarter fewer dot products).
template <typename Visit>
bool ForEachAxis(const Triangle3d& a, const Vector3d& na, const Triangle3d& b, const Vector3d& nb,
                 Visit&& visit) {
  const std::array<Vector3d, 3> ea = {a[1] - a[0], a[2] - a[1], a[0] - a[2]};
  const std::array<Vector3d, 3> eb = {b[1] - b[0], b[2] - b[1], b[0] - b[2]};
  auto usable = [](const Vector3d& axis, double scale_sq, double& norm_sq) {
    norm_sq = axis.squaredNorm();
    return norm_sq > kAxisRelativeFloor * kAxisRelativeFloor * scale_sq && norm_sq != 0;
  };
  const double la[3] = {ea[0].squaredNorm(), ea[1].squaredNorm(), ea[2].squaredNorm()};
  const double lb[3] = {eb[0].squaredNorm(), eb[1].squaredNorm(), eb[2].squaredNorm()};
  const double la_max = std::max(std::max(la[0], la[1]), la[2]);
  const double lb_max = std::max(std::max(lb[0], lb[1]), lb[2]);
  double norm_sq;
  if (usable(na, la_max * la_max, norm_sq)) {
    const double at = na.dot(a[0]);
    if (!visit(na, norm_sq, Extent{at, at}, ProjectThree(na, b))) return false;
  }
  if (usable(nb, lb_max * lb_max, norm_sq)) {
    const double at = nb.dot(b[0]);
    if (!visit(nb, norm_sq, ProjectThree(nb, a), Extent{at, at})) return false;
  }
  // Edge i joins corners i and i + 1; corner i + 2 is off it.
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const Vector3d axis = ea[i].cross(eb[j]);
      if (usable(axis, la[i] * lb[j], norm_sq) &&
          !visit(axis, norm_sq, ProjectTwo(axis, a[i], a[(i + 2) % 3]),
                 ProjectTwo(axis, b[j], b[(j + 2) % 3]))) {
        return false;
      }
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
    if (usable(axis_a, la_max * la_max * la[i], norm_sq) &&
        !visit(axis_a, norm_sq, ProjectTwo(axis_a, a[i], a[(i + 2) % 3]),
               ProjectThree(axis_a, b))) {
      return false;
    }
    const Vector3d axis_b = nb.cross(eb[i]);
    if (usable(axis_b, lb_max * lb_max * lb[i], norm_sq) &&
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

// Where `t` crosses the other triangle's plane, as an interval of the
// parameter p.dot(line) along the planes' common line, given its corners'
// distances `d` from that plane; none when no corner stands clear of the
// plane on each side (by more than `clear`).
std::optional<Extent> CrossingOnLine(const Triangle3d& t, const std::array<double, 3>& d,
                                     double clear, const Vector3d& line, const Vector3d& origin) {
  // The corner alone on its side, and the other two.
  int lone = -1;
  for (int i = 0; i < 3; ++i) {
    if (std::abs(d[i]) <= clear) return std::nullopt;
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    if ((d[i] > 0) != (d[j] > 0) && (d[i] > 0) != (d[k] > 0)) lone = i;
  }
  if (lone < 0) return std::nullopt;
  const double at_lone = line.dot(t[lone] - origin);
  double ends[2];
  for (int n = 1; n <= 2; ++n) {
    const int i = (lone + n) % 3;
    const double at_i = line.dot(t[i] - origin);
    ends[n - 1] = at_i + (at_lone - at_i) * d[i] / (d[i] - d[lone]);
  }
  return Extent{std::min(ends[0], ends[1]), std::max(ends[0], ends[1])};
}

// Relative to the triangles' size, what rounding cannot reach: the fast
// crossing test below answers only when every quantity it compares stands
// clear of zero by this much, and leaves every other pair to the SAT.
constexpr double kClearlyRelative = 1e-9;

// A fast yes for triangles that cross each other (Moller's interval test):
// each straddles the other's plane, and the two segments where they cut the
// planes' common line overlap. Both segments lie on that line inside both
// triangles, so an overlap is a common point. Only a clear yes counts.
bool ClearlyCrossing(const Triangle3d& a, const Vector3d& na, const std::array<double, 3>& da,
                     const Triangle3d& b, const Vector3d& nb, const std::array<double, 3>& db) {
  const double size = (a[0] - b[0]).cwiseAbs().maxCoeff() + (a[1] - a[0]).cwiseAbs().maxCoeff() +
                      (a[2] - a[0]).cwiseAbs().maxCoeff() + (b[1] - b[0]).cwiseAbs().maxCoeff() +
                      (b[2] - b[0]).cwiseAbs().maxCoeff();
  const double clear = kClearlyRelative * size;
  const Vector3d line = na.cross(nb);
  const double line_norm = line.norm();
  if (!(line_norm > 0)) return false;
  const std::optional<Extent> on_a = CrossingOnLine(a, da, clear * nb.norm(), line, b[0]);
  if (!on_a) return false;
  const std::optional<Extent> on_b = CrossingOnLine(b, db, clear * na.norm(), line, b[0]);
  if (!on_b) return false;
  return std::min(on_a->hi, on_b->hi) - std::max(on_a->lo, on_b->lo) > clear * line_norm;
}

}  // namespace

Vector3d TriangleNormal(const Triangle3d& t) { return (t[1] - t[0]).cross(t[2] - t[1]); }

bool TrianglesIntersect(const Triangle3d& a, const Triangle3d& b, double margin) {
  return TrianglesIntersect(a, TriangleNormal(a), b, TriangleNormal(b), margin);
}

bool TrianglesIntersect(const Triangle3d& a, const Vector3d& normal_a, const Triangle3d& b,
                        const Vector3d& normal_b, double margin) {
  const std::array<double, 3> db = PlaneDistances(b, a[0], normal_a);
  if (BeyondPlane(db, normal_a, margin)) return false;
  const std::array<double, 3> da = PlaneDistances(a, b[0], normal_b);
  if (BeyondPlane(da, normal_b, margin)) return false;
  if (ClearlyCrossing(a, normal_a, da, b, normal_b, db)) return true;
  return ForEachAxis(a, normal_a, b, normal_b,
                     [&](const Vector3d&, double norm_sq, const Extent& ea, const Extent& eb) {
                       return !SeparatedAlong(ea.lo, ea.hi, eb.lo, eb.hi, norm_sq, margin);
                     });
}

Interval SweptIntersection(const Triangle3d& a, const Triangle3d& b, const Vector3d& direction,
                           double margin, Interval within) {
  return SweptIntersection(a, TriangleNormal(a), b, TriangleNormal(b), direction, margin, within);
}

Interval SweptIntersection(const Triangle3d& a, const Vector3d& normal_a, const Triangle3d& b,
                           const Vector3d& normal_b, const Vector3d& direction, double margin,
                           Interval within) {
  Interval result = within;
  ForEachAxis(a, normal_a, b, normal_b,
              [&](const Vector3d& axis, double norm_sq, const Extent& ea, const Extent& eb) {
                const double slack = margin != 0 ? margin * std::sqrt(norm_sq) : 0.0;
                // Along the axis, a(t) spans [ea.lo - t*s, ea.hi - t*s] with
                // s = axis.D. They overlap while ea.lo - t*s <= eb.hi + slack
                // and eb.lo <= ea.hi - t*s + slack.
                const double s = axis.dot(direction);
                const double low_gap = ea.lo - eb.hi - slack;   // need t*s >= low_gap
                const double high_gap = ea.hi - eb.lo + slack;  // need t*s <= high_gap
                if (s == 0) {
                  if (low_gap > 0 || high_gap < 0) result = Interval{};
                } else {
                  const double inverse = 1 / s;
                  const double from_low = low_gap * inverse, from_high = high_gap * inverse;
                  result.lo = std::max(result.lo, s > 0 ? from_low : from_high);
                  result.hi = std::min(result.hi, s > 0 ? from_high : from_low);
                }
                return !result.empty();
              });
  return result;
}

}  // namespace hs

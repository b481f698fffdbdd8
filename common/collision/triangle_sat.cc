#include "common/collision/triangle_sat.h"

#include <algorithm>
#include <cmath>

namespace hs {
namespace {

// Below this (relative to the product of the lengths that formed it) an axis
// is a rounding artefact of parallel edges or a flat face, and is skipped.
constexpr double kAxisRelativeFloor = 1e-12;

// Calls visit(axis, squared_axis_norm) for every usable SAT axis of the pair; stops
// early and returns false when visit returns false.
// `na` and `nb` are the face normals (a[1]-a[0]) x (a[2]-a[1]), unnormalised.
template <typename Visit>
bool ForEachAxis(const Triangle3d& a, const Vector3d& na, const Triangle3d& b, const Vector3d& nb,
                 Visit&& visit) {
  const std::array<Vector3d, 3> ea = {a[1] - a[0], a[2] - a[1], a[0] - a[2]};
  const std::array<Vector3d, 3> eb = {b[1] - b[0], b[2] - b[1], b[0] - b[2]};
  auto try_axis = [&](const Vector3d& axis, double scale_sq) {
    const double norm_sq = axis.squaredNorm();
    if (norm_sq <= kAxisRelativeFloor * kAxisRelativeFloor * scale_sq || norm_sq == 0) return true;
    return visit(axis, norm_sq);
  };
  const double la[3] = {ea[0].squaredNorm(), ea[1].squaredNorm(), ea[2].squaredNorm()};
  const double lb[3] = {eb[0].squaredNorm(), eb[1].squaredNorm(), eb[2].squaredNorm()};
  const double la_max = std::max({la[0], la[1], la[2]});
  const double lb_max = std::max({lb[0], lb[1], lb[2]});
  if (!try_axis(na, la_max * la_max)) return false;
  if (!try_axis(nb, lb_max * lb_max)) return false;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (!try_axis(ea[i].cross(eb[j]), la[i] * lb[j])) return false;
    }
  }
  for (int i = 0; i < 3; ++i) {
    if (!try_axis(na.cross(ea[i]), la_max * la_max * la[i])) return false;
    if (!try_axis(nb.cross(eb[i]), lb_max * lb_max * lb[i])) return false;
  }
  return true;
}

void Project(const Triangle3d& t, const Vector3d& axis, double& lo, double& hi) {
  const double p0 = axis.dot(t[0]), p1 = axis.dot(t[1]), p2 = axis.dot(t[2]);
  lo = std::min(std::min(p0, p1), p2);
  hi = std::max(std::max(p0, p1), p2);
}

// True when the gap between [a_lo, a_hi] and [b_lo, b_hi] along an axis of
// squared length `norm_sq` exceeds `margin` (in metres, so scaled by the
// axis length); squares avoid a square root per axis.
bool SeparatedAlong(double a_lo, double a_hi, double b_lo, double b_hi, double norm_sq,
                    double margin) {
  const double gap = std::max(a_lo - b_hi, b_lo - a_hi);
  return gap > 0 && gap * gap > margin * margin * norm_sq;
}

// Whether all of `t` lies beyond `margin` on one side of the plane through
// `origin` with normal `n`: the cheap first test of the leaf, which rejects
// most candidate pairs before the full axis set is built.
bool BeyondPlane(const Triangle3d& t, const Vector3d& origin, const Vector3d& n, double margin) {
  const double norm_sq = n.squaredNorm();
  if (norm_sq == 0) return false;
  const double d0 = n.dot(t[0] - origin), d1 = n.dot(t[1] - origin), d2 = n.dot(t[2] - origin);
  const double lo = std::min(std::min(d0, d1), d2), hi = std::max(std::max(d0, d1), d2);
  return SeparatedAlong(lo, hi, 0.0, 0.0, norm_sq, margin);
}

}  // namespace

Vector3d TriangleNormal(const Triangle3d& t) { return (t[1] - t[0]).cross(t[2] - t[1]); }

bool TrianglesIntersect(const Triangle3d& a, const Triangle3d& b, double margin) {
  return TrianglesIntersect(a, TriangleNormal(a), b, TriangleNormal(b), margin);
}

bool TrianglesIntersect(const Triangle3d& a, const Vector3d& normal_a, const Triangle3d& b,
                        const Vector3d& normal_b, double margin) {
  if (BeyondPlane(b, a[0], normal_a, margin)) return false;
  if (BeyondPlane(a, b[0], normal_b, margin)) return false;
  return ForEachAxis(a, normal_a, b, normal_b, [&](const Vector3d& axis, double norm_sq) {
    double a_lo, a_hi, b_lo, b_hi;
    Project(a, axis, a_lo, a_hi);
    Project(b, axis, b_lo, b_hi);
    return !SeparatedAlong(a_lo, a_hi, b_lo, b_hi, norm_sq, margin);
  });
}

Interval SweptIntersection(const Triangle3d& a, const Triangle3d& b, const Vector3d& direction,
                           double margin, Interval within) {
  Interval result = within;
  ForEachAxis(a, TriangleNormal(a), b, TriangleNormal(b),
              [&](const Vector3d& axis, double norm_sq) {
                double a_lo, a_hi, b_lo, b_hi;
                Project(a, axis, a_lo, a_hi);
                Project(b, axis, b_lo, b_hi);
                const double slack = margin * std::sqrt(norm_sq);
                // Along the axis, a(t) spans [a_lo - t*s, a_hi - t*s] with s = axis.D.
                // They overlap while a_lo - t*s <= b_hi + slack and b_lo <= a_hi - t*s + slack.
                const double s = axis.dot(direction);
                const double low_gap = a_lo - b_hi - slack;   // need t*s >= low_gap
                const double high_gap = a_hi - b_lo + slack;  // need t*s <= high_gap
                if (s == 0) {
                  if (low_gap > 0 || high_gap < 0) result = Interval{};
                } else if (s > 0) {
                  result.lo = std::max(result.lo, low_gap / s);
                  result.hi = std::min(result.hi, high_gap / s);
                } else {
                  result.lo = std::max(result.lo, high_gap / s);
                  result.hi = std::min(result.hi, low_gap / s);
                }
                return !result.empty();
              });
  return result;
}

}  // namespace hs

#include "common/contact/closest_points.h"

#include <algorithm>

namespace hs {

Vector3d ClosestPointOnSegment(const Vector3d& p, const Vector3d& a, const Vector3d& b) {
  const Vector3d ab = b - a;
  const double length_sq = ab.squaredNorm();
  if (length_sq == 0) return a;
  return a + std::clamp((p - a).dot(ab) / length_sq, 0.0, 1.0) * ab;
}

Vector3d ClosestPointOnTriangle(const Vector3d& p, const Vector3d& a, const Vector3d& b,
                                const Vector3d& c) {
  const Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
  const Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  }
  const double denominator = va + vb + vc;
  if (!(denominator > 0)) {
    // Degenerate (zero-area) triangle: the best of its three segments.
    const Vector3d candidates[3] = {ClosestPointOnSegment(p, a, b), ClosestPointOnSegment(p, b, c),
                                    ClosestPointOnSegment(p, c, a)};
    return *std::min_element(std::begin(candidates), std::end(candidates),
                             [&](const Vector3d& x, const Vector3d& y) {
                               return (x - p).squaredNorm() < (y - p).squaredNorm();
                             });
  }
  return a + ab * (vb / denominator) + ac * (vc / denominator);
}

SegmentClosest ClosestPointsOfSegments(const Vector3d& p1, const Vector3d& q1, const Vector3d& p2,
                                       const Vector3d& q2) {
  const Vector3d d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  SegmentClosest out;
  if (a == 0 && e == 0) {
    out.on_first = p1;
    out.on_second = p2;
    return out;
  }
  if (a == 0) {
    out.t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (e == 0) {
      out.s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2);
      const double denominator = a * e - b * b;
      // Parallel segments (denominator 0): any s works; take 0.
      out.s = denominator > 0 ? std::clamp((b * f - c * e) / denominator, 0.0, 1.0) : 0.0;
      out.t = (b * out.s + f) / e;
      if (out.t < 0) {
        out.t = 0;
        out.s = std::clamp(-c / a, 0.0, 1.0);
      } else if (out.t > 1) {
        out.t = 1;
        out.s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  out.on_first = p1 + out.s * d1;
  out.on_second = p2 + out.t * d2;
  return out;
}

}  // namespace hs

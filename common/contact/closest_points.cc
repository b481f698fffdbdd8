#include "common/contact/closest_points.h"

#include <algorithm>

namespace hs {

Vector3d ClosestPointOnSegment(const Vector3d& p, const Vector3d& a, const Vector3d& b) {
  const Vector3d ab = b - a;
  const double length_sq = ab.squaredNorm();
  if (length_sq == 0) return a;
  return a + std::clamp((p - a).dot(ab) / length_sq, 0.0, 1.0) * ab;
}

namespace {

// Triangles with twice their area at most this times their longest edge
// squared are slivers to ClosestPointOnTriangle.
constexpr double kSliver = 1e-4;

// The point of a sliver closest to `p`: the nearest of its edges' points and
// of the foot of p on its plane, when that lies in it (with the plane's
// normal from the corners alone, not from p's distances).
Vector3d ClosestPointOnSliver(const Vector3d& p, const Vector3d& a, const Vector3d& b,
                              const Vector3d& c) {
  Vector3d best = ClosestPointOnSegment(p, a, b);
  for (const Vector3d& q : {ClosestPointOnSegment(p, b, c), ClosestPointOnSegment(p, c, a)}) {
    if ((q - p).squaredNorm() < (best - p).squaredNorm()) best = q;
  }
  const Vector3d n = (b - a).cross(c - a);
  const double n_sq = n.squaredNorm();
  if (!(n_sq > 0)) return best;
  const Vector3d foot = p - n * (n.dot(p - a) / n_sq);
  const bool inside = n.dot((b - a).cross(foot - a)) >= 0 && n.dot((c - b).cross(foot - b)) >= 0 &&
                      n.dot((a - c).cross(foot - c)) >= 0;
  return inside && (foot - p).squaredNorm() < (best - p).squaredNorm() ? foot : best;
}

}  // namespace

Vector3d ClosestPointOnTriangle(const Vector3d& p, const Vector3d& a, const Vector3d& b,
                                const Vector3d& c) {
  const Vector3d ab = b - a, ac = c - a, ap = p - a;
  // The region tests below decide by the signs of products of p's distances
  // that cancel, and the face formula divides by their sum (|ab x ac|^2):
  // on a sliver, or a zero-area triangle, both are rounding noise.
  const double longest_sq = std::max({ab.squaredNorm(), ac.squaredNorm(), (c - b).squaredNorm()});
  if (!(ab.cross(ac).squaredNorm() > kSliver * kSliver * longest_sq * longest_sq)) {
    return ClosestPointOnSliver(p, a, b, c);
  }
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

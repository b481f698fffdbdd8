#include "tests/common/contact/brute_force_depth.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace hs::reference {
namespace {

// long double (x87 80-bit on amd64: 64-bit mantissa) so that the oracle's
// rounding is ~2000x below the double method's it checks.
using Real = long double;
using Vec = Eigen::Matrix<Real, 3, 1>;
using Tri = std::array<Vec, 3>;

constexpr Real kInf = std::numeric_limits<Real>::infinity();

// An axis this much shorter than the lengths that formed it is a rounding
// artefact of parallel edges or a flat face: exact arithmetic would give 0.
// Far below the method's 1e-12, so that only true artefacts are skipped.
constexpr Real kAxisRelativeFloor = 1e-15L;

struct Extent {
  Real lo, hi;
};

Extent Project(const Vec& axis, const Tri& t) {
  const Real x = axis.dot(t[0]), y = axis.dot(t[1]), z = axis.dot(t[2]);
  return {std::min({x, y, z}), std::max({x, y, z})};
}

// The t in [0, inf) for which `a` moved by -t D meets `b` (zero margin), by
// the separating axis theorem over the same 17 axes as the method (two
// face normals, nine edge crosses, six in-plane edge normals); lo > hi
// when empty. Face normals go first: they reject most pairs alone.
std::pair<Real, Real> SweepInterval(const Tri& a, const Tri& b, const Vec& D) {
  const std::array<Vec, 3> ea = {a[1] - a[0], a[2] - a[1], a[0] - a[2]};
  const std::array<Vec, 3> eb = {b[1] - b[0], b[2] - b[1], b[0] - b[2]};
  const Vec na = ea[0].cross(ea[1]), nb = eb[0].cross(eb[1]);
  std::array<Vec, 17> axes;
  std::array<Real, 17> scales;  // squared lengths that formed each axis
  int n = 0;
  const Real la = std::max({ea[0].squaredNorm(), ea[1].squaredNorm(), ea[2].squaredNorm()});
  const Real lb = std::max({eb[0].squaredNorm(), eb[1].squaredNorm(), eb[2].squaredNorm()});
  axes[n] = na, scales[n++] = la * la;
  axes[n] = nb, scales[n++] = lb * lb;
  for (const Vec& u : ea) {
    for (const Vec& v : eb) axes[n] = u.cross(v), scales[n++] = u.squaredNorm() * v.squaredNorm();
  }
  for (const Vec& u : ea) axes[n] = na.cross(u), scales[n++] = la * la * u.squaredNorm();
  for (const Vec& v : eb) axes[n] = nb.cross(v), scales[n++] = lb * lb * v.squaredNorm();
  Real lo = 0, hi = kInf;
  for (int i = 0; i < n && lo <= hi; ++i) {
    const Real norm_sq = axes[i].squaredNorm();
    if (!(norm_sq > kAxisRelativeFloor * kAxisRelativeFloor * scales[i])) continue;
    const Extent pa = Project(axes[i], a), pb = Project(axes[i], b);
    // a(t) spans [pa.lo - t s, pa.hi - t s]; it overlaps b while
    // t s >= pa.lo - pb.hi and t s <= pa.hi - pb.lo.
    const Real s = axes[i].dot(D);
    const Real low_gap = pa.lo - pb.hi, high_gap = pa.hi - pb.lo;
    if (s == 0) {
      if (low_gap > 0 || high_gap < 0) return {kInf, -kInf};
    } else if (s > 0) {
      lo = std::max(lo, low_gap / s), hi = std::min(hi, high_gap / s);
    } else {
      lo = std::max(lo, high_gap / s), hi = std::min(hi, low_gap / s);
    }
  }
  return {lo, hi};
}

// The object's triangles in the world frame, posed in long double.
std::vector<Tri> WorldTriangles(const PosedObject& posed) {
  const Eigen::Matrix<Real, 3, 3> R = posed.X_WO.linear().cast<Real>();
  const Vec p = posed.X_WO.translation().cast<Real>();
  std::vector<Vec> positions;
  for (const Vector3d& v : posed.object->positions()) positions.push_back(R * v.cast<Real>() + p);
  std::vector<Tri> triangles;
  for (const Face& f : posed.object->faces()) {
    triangles.push_back(
        {positions[f.vertices[0]], positions[f.vertices[1]], positions[f.vertices[2]]});
  }
  return triangles;
}

}  // namespace

BruteForceDepth ComputeBruteForceDepth(const PosedObject& moving, const PosedObject& fixed,
                                       const Vector3d& direction_W, double relative_tolerance) {
  BruteForceDepth result;
  result.tolerance_m = static_cast<Real>(relative_tolerance) *
                       (static_cast<Real>(moving.object->bounding_box().diagonal().norm()) +
                        static_cast<Real>(fixed.object->bounding_box().diagonal().norm()));
  const Vec D = direction_W.cast<Real>().normalized();
  const std::vector<Tri> a = WorldTriangles(moving), b = WorldTriangles(fixed);
  std::vector<std::pair<Real, Real>> intervals;
  for (const Tri& ta : a) {
    for (const Tri& tb : b) {
      const auto interval = SweepInterval(ta, tb, D);
      if (interval.first <= interval.second) intervals.push_back(interval);
    }
  }
  result.pairs = static_cast<int64_t>(a.size()) * static_cast<int64_t>(b.size());
  result.meeting_pairs = static_cast<int64_t>(intervals.size());
  std::sort(intervals.begin(), intervals.end());
  // Intervals start at t >= 0; those starting within the tolerance of 0
  // meet now, and each one starting within it of the run's end extends it.
  Real t_star = 0;
  for (const auto& [lo, hi] : intervals) {
    if (lo > t_star + result.tolerance_m) break;
    result.colliding = true;
    t_star = std::max(t_star, hi);
  }
  result.depth_m = t_star;
  return result;
}

}  // namespace hs::reference

// SweptPlaneBounds over several faces at once (plane_bounds_batch.h):
// written by hand with Google Highway because no library does this one
// cut, and it must give the scalar cut's numbers bit for bit. Every
// operation is the scalar one in the scalar order: no fused multiply-add
// (Highway's MulAdd is never used, and the build compiles this file with
// -ffp-contract=off), std::min and std::max as their comparisons, the
// scalar's branches as lane masks.

#include "common/collision/plane_bounds_batch.h"

#include <algorithm>
#include <limits>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "common/collision/plane_bounds_batch.cc"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"
// After highway.h: compiled for each target.
#include "common/collision/scalar_order-inl.h"

HWY_BEFORE_NAMESPACE();
namespace hs {
namespace HWY_NAMESPACE {

// The faces of one batch, a lane each: corner k's coordinates.
struct Corners {
  V x[3], y[3], z[3];
};

// A face's normal (TriangleNormal), its squared length and the largest
// squared length of its edges, as ForEachAxis makes them.
struct FaceAxis {
  V nx, ny, nz, norm_sq, longest_edge_sq;
};

HWY_INLINE FaceAxis FaceAxisOf(const Corners& c) {
  V ex[3], ey[3], ez[3], len[3];
  for (int k = 0; k < 3; ++k) {
    const int next = (k + 1) % 3;
    ex[k] = hn::Sub(c.x[next], c.x[k]);
    ey[k] = hn::Sub(c.y[next], c.y[k]);
    ez[k] = hn::Sub(c.z[next], c.z[k]);
    len[k] = Dot(ex[k], ey[k], ez[k], ex[k], ey[k], ez[k]);
  }
  FaceAxis f;
  f.nx = hn::Sub(hn::Mul(ey[0], ez[1]), hn::Mul(ez[0], ey[1]));
  f.ny = hn::Sub(hn::Mul(ez[0], ex[1]), hn::Mul(ex[0], ez[1]));
  f.nz = hn::Sub(hn::Mul(ex[0], ey[1]), hn::Mul(ey[0], ex[1]));
  f.norm_sq = Dot(f.nx, f.ny, f.nz, f.nx, f.ny, f.nz);
  f.longest_edge_sq = MaxOf(MaxOf(len[0], len[1]), len[2]);
  return f;
}

// UsableAxis for a face's normal: long enough against its edges to trust.
template <class DD>
HWY_INLINE hn::Mask<DD> Usable(DD d, const FaceAxis& f) {
  const V floor = hn::Mul(hn::Set(d, kAxisRelativeFloor * kAxisRelativeFloor),
                          hn::Mul(f.longest_edge_sq, f.longest_edge_sq));
  return hn::And(hn::Gt(f.norm_sq, floor), hn::Ne(f.norm_sq, hn::Zero(d)));
}

// Projections of a batch's corners on per-lane axes: the least and most.
HWY_INLINE void Project(const FaceAxis& axis, const Corners& c, V& lo, V& hi) {
  const V p0 = Dot(axis.nx, axis.ny, axis.nz, c.x[0], c.y[0], c.z[0]);
  const V p1 = Dot(axis.nx, axis.ny, axis.nz, c.x[1], c.y[1], c.z[1]);
  const V p2 = Dot(axis.nx, axis.ny, axis.nz, c.x[2], c.y[2], c.z[2]);
  lo = MinOf(MinOf(p0, p1), p2);
  hi = MaxOf(MaxOf(p0, p1), p2);
}

struct Intervals {
  V lo[2], hi[2];
};

// CutToSweep's visit for the two margins {margin, 0}, in the lanes of
// `active`: the axis has squared length `norm_sq` and direction dot `s`;
// a spans [a_lo, a_hi] along it, b [b_lo, b_hi].
HWY_INLINE void Cut(D d, M active, V norm_sq, V s, V a_lo, V a_hi, V b_lo, V b_hi, double margin,
                    Intervals& r) {
  const V zero = hn::Zero(d);
  const M s_zero = hn::Eq(s, zero);
  const V inverse = hn::IfThenElse(s_zero, zero, hn::Div(hn::Set(d, 1.0), s));
  const V length = margin != 0 ? hn::Sqrt(norm_sq) : zero;
  const M s_positive = hn::Gt(s, zero);
  const double margins[2] = {margin, 0.0};
  for (int k = 0; k < 2; ++k) {
    const V slack = hn::Mul(hn::Set(d, margins[k]), length);
    const V low_gap = hn::Sub(hn::Sub(a_lo, b_hi), slack);
    const V high_gap = hn::Add(hn::Sub(a_hi, b_lo), slack);
    // s == 0: apart for every t, or not cut at all.
    const M apart = hn::And(s_zero, hn::Or(hn::Gt(low_gap, zero), hn::Lt(high_gap, zero)));
    const V from_low = hn::Mul(low_gap, inverse), from_high = hn::Mul(high_gap, inverse);
    const V lo = MaxOf(r.lo[k], hn::IfThenElse(s_positive, from_low, from_high));
    const V hi = MinOf(r.hi[k], hn::IfThenElse(s_positive, from_high, from_low));
    const M cut = hn::AndNot(s_zero, active);
    r.lo[k] = hn::IfThenElse(cut, lo, r.lo[k]);
    r.hi[k] = hn::IfThenElse(cut, hi, r.hi[k]);
    const M emptied = hn::And(apart, active);
    r.lo[k] = hn::IfThenElse(emptied, hn::Set(d, std::numeric_limits<double>::infinity()), r.lo[k]);
    r.hi[k] =
        hn::IfThenElse(emptied, hn::Set(d, -std::numeric_limits<double>::infinity()), r.hi[k]);
  }
}

// Loads faces[first, first + lanes) into lanes (a short last batch
// repeats its last face).
HWY_INLINE void Transpose(const TriangleCorners* faces, size_t first, size_t count, size_t lanes,
                          double* soa, size_t stride, Corners& c, const D d) {
  for (size_t j = 0; j < lanes; ++j) {
    const TriangleCorners& t = faces[first + std::min(j, count - 1)];
    for (int k = 0; k < 3; ++k) {
      soa[(3 * k) * stride + j] = t[k]->x();
      soa[(3 * k + 1) * stride + j] = t[k]->y();
      soa[(3 * k + 2) * stride + j] = t[k]->z();
    }
  }
  for (int k = 0; k < 3; ++k) {
    c.x[k] = hn::Load(d, soa + (3 * k) * stride);
    c.y[k] = hn::Load(d, soa + (3 * k + 1) * stride);
    c.z[k] = hn::Load(d, soa + (3 * k + 2) * stride);
  }
}

void SweptPlaneBoundsLanes(const TriangleCorners* a, const TriangleCorners* b, size_t n,
                           const Vector3d& direction, double margin, Interval within,
                           SweptIntervals* out) {
  const D d;
  const size_t lanes = hn::Lanes(d);
  const V dx = hn::Set(d, direction.x()), dy = hn::Set(d, direction.y()),
          dz = hn::Set(d, direction.z());
  constexpr size_t kMaxLanes = HWY_MAX_BYTES / sizeof(double);
  HWY_ALIGN double soa[9 * kMaxLanes];
  HWY_ALIGN double lo[2][kMaxLanes], hi[2][kMaxLanes];
  for (size_t first = 0; first < n; first += lanes) {
    const size_t count = std::min(lanes, n - first);
    Corners ca, cb;
    Transpose(a, first, count, lanes, soa, kMaxLanes, ca, d);
    Transpose(b, first, count, lanes, soa, kMaxLanes, cb, d);
    Intervals r;
    for (int k = 0; k < 2; ++k) {
      r.lo[k] = hn::Set(d, within.lo);
      r.hi[k] = hn::Set(d, within.hi);
    }
    const FaceAxis na = FaceAxisOf(ca), nb = FaceAxisOf(cb);
    // Axis 1, a's normal: a at one point, b's corners projected.
    const auto usable_a = Usable(d, na);
    {
      const V at = Dot(na.nx, na.ny, na.nz, ca.x[0], ca.y[0], ca.z[0]);
      const V s = Dot(na.nx, na.ny, na.nz, dx, dy, dz);
      V b_lo, b_hi;
      Project(na, cb, b_lo, b_hi);
      Cut(d, usable_a, na.norm_sq, s, at, at, b_lo, b_hi, margin, r);
    }
    // Axis 2, b's normal; after a usable first axis, only where the
    // margin's interval is not empty yet (the scalar pass stops there).
    {
      const auto open = hn::Or(hn::Not(usable_a), hn::Not(hn::Gt(r.lo[0], r.hi[0])));
      const V at = Dot(nb.nx, nb.ny, nb.nz, cb.x[0], cb.y[0], cb.z[0]);
      const V s = Dot(nb.nx, nb.ny, nb.nz, dx, dy, dz);
      V a_lo, a_hi;
      Project(nb, ca, a_lo, a_hi);
      Cut(d, hn::And(Usable(d, nb), open), nb.norm_sq, s, a_lo, a_hi, at, at, margin, r);
    }
    for (int k = 0; k < 2; ++k) {
      hn::Store(r.lo[k], d, lo[k]);
      hn::Store(r.hi[k], d, hi[k]);
    }
    for (size_t j = 0; j < count; ++j) {
      out[first + j] = {.exact = {lo[1][j], hi[1][j]}, .within_margin = {lo[0][j], hi[0][j]}};
    }
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace hs
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace hs {

HWY_EXPORT(SweptPlaneBoundsLanes);

void SweptPlaneBoundsBatch(std::span<const TriangleCorners> a, std::span<const TriangleCorners> b,
                           const Vector3d& direction, double margin, Interval within,
                           std::span<SweptIntervals> out) {
  HWY_DYNAMIC_DISPATCH(SweptPlaneBoundsLanes)
  (a.data(), b.data(), b.size(), direction, margin, within, out.data());
}

}  // namespace hs
#endif

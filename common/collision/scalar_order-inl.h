// The scalar code's arithmetic in SIMD lanes, for the batched kernels that
// must give its numbers bit for bit (plane_bounds_batch.cc,
// face_test_batch.cc and others): std::min and std::max as their
// comparisons, and Eigen's products of 3-vectors in its order. Compiled once per Highway
// target by each file that includes it after hwy/highway.h (Highway's
// per-target include guard below); their files are built with
// -ffp-contract=off, so no product and sum fuse.

#if defined(HS_COLLISION_SCALAR_ORDER_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef HS_COLLISION_SCALAR_ORDER_INL_H_
#undef HS_COLLISION_SCALAR_ORDER_INL_H_
#else
#define HS_COLLISION_SCALAR_ORDER_INL_H_
#endif

#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace hs {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

/// The lanes the batched kernels work in: doubles, as many as the target
/// holds, a face or face pair each.
using D = hn::ScalableTag<double>;
using V = hn::Vec<D>;
using M = hn::Mask<D>;

/// std::min(a, b) and std::max(a, b), lane by lane, NaNs and signed zeros
/// included.
HWY_INLINE V MinOf(V a, V b) { return hn::IfThenElse(hn::Lt(b, a), b, a); }
HWY_INLINE V MaxOf(V a, V b) { return hn::IfThenElse(hn::Lt(a, b), b, a); }

/// Eigen's dot product (and squared norm) of 3-vectors, in its order.
HWY_INLINE V Dot(V ax, V ay, V az, V bx, V by, V bz) {
  return hn::Add(hn::Add(hn::Mul(ax, bx), hn::Mul(ay, by)), hn::Mul(az, bz));
}

/// A 3-vector a lane, and Eigen's difference, dot and cross products of
/// such, in its order.
struct Point {
  V x, y, z;
};
HWY_INLINE Point Minus(const Point& p, const Point& q) {
  return {hn::Sub(p.x, q.x), hn::Sub(p.y, q.y), hn::Sub(p.z, q.z)};
}
HWY_INLINE V Dot(const Point& p, const Point& q) { return Dot(p.x, p.y, p.z, q.x, q.y, q.z); }
HWY_INLINE Point Cross(const Point& p, const Point& q) {
  return {hn::Sub(hn::Mul(p.y, q.z), hn::Mul(p.z, q.y)),
          hn::Sub(hn::Mul(p.z, q.x), hn::Mul(p.x, q.z)),
          hn::Sub(hn::Mul(p.x, q.y), hn::Mul(p.y, q.x))};
}

}  // namespace HWY_NAMESPACE
}  // namespace hs
HWY_AFTER_NAMESPACE();

#endif  // HS_COLLISION_SCALAR_ORDER_INL_H_

// The contact locator's first tests over several face pairs at once
// (near_features_batch.h): written by hand with Google Highway because no
// library does these tests, and they must give the scalar comparisons'
// answers bit for bit. Every operation is the scalar one in the scalar
// order: no fused multiply-add (the build compiles this file with
// -ffp-contract=off), std::min and std::max as their comparisons, Eigen's
// products in its order (common/collision/scalar_order-inl.h). The faces
// are loaded from the callers' arrays into lanes (lane_rows-inl.h).

#include "common/contact/near_features_batch.h"

#include <algorithm>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "common/contact/near_features_batch.cc"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"
// After highway.h: compiled for each target.
#include "common/collision/lane_rows-inl.h"
#include "common/collision/scalar_order-inl.h"

HWY_BEFORE_NAMESPACE();
namespace hs {
namespace HWY_NAMESPACE {

constexpr int64_t kMovingDoubles = sizeof(MovingFaceCorners) / sizeof(double);
constexpr int64_t kFixedDoubles = sizeof(FixedFaceEdges) / sizeof(double);
static_assert(sizeof(MovingFaceCorners) == 12 * sizeof(double),
              "a MovingFaceCorners is 12 packed doubles");
static_assert(sizeof(FixedFaceEdges) == 51 * sizeof(double),
              "a FixedFaceEdges is 51 packed doubles");

Point Column(const V* column, int first) {
  return {column[first], column[first + 1], column[first + 2]};
}

// The bits of one test, lane by lane: `bit` where `m`, else 0.
V Bit(D d, M m, double bit) { return hn::IfThenElseZero(m, hn::Set(d, bit)); }

void NearFeaturesLanes(const MovingFaceCorners* moving, const FixedFaceEdges* fixed,
                       const FaceRecordPair* pairs, size_t n, double tolerance, double corner_slack,
                       NearFeatures* out) {
  const D d;
  const size_t lanes = hn::Lanes(d);
  constexpr size_t kMaxLanes = HWY_MAX_BYTES / sizeof(double);
  HWY_ALIGN int64_t offset_m[kMaxLanes], offset_f[kMaxLanes];
  HWY_ALIGN double soa[24 * kMaxLanes];
  HWY_ALIGN double bits[kMaxLanes];
  const auto* base_m = reinterpret_cast<const double*>(moving);
  const auto* base_f = reinterpret_cast<const double*>(fixed);
  const V tol = hn::Set(d, tolerance), neg_tol = hn::Set(d, -tolerance);
  const V twice_tol = hn::Set(d, 2 * tolerance), neg_twice_tol = hn::Set(d, -2 * tolerance);
  const V slack = hn::Set(d, corner_slack);
  for (size_t first = 0; first < n; first += lanes) {
    // A short last batch repeats its last pair.
    const size_t count = std::min(lanes, n - first);
    for (size_t j = 0; j < lanes; ++j) {
      const FaceRecordPair& pair = pairs[first + std::min(j, count - 1)];
      offset_m[RowOfLane(j)] = pair.moving * kMovingDoubles;
      offset_f[RowOfLane(j)] = pair.fixed * kFixedDoubles;
    }
    V mc[12], fc[24];
    LoadColumns<3>(d, base_m, offset_m, soa, kMaxLanes, mc);
    LoadColumns<6>(d, base_f, offset_f, soa, kMaxLanes, fc);
    const Point m[3] = {Column(mc, 0), Column(mc, 3), Column(mc, 6)};
    const Point f[3] = {Column(fc, 0), Column(fc, 3), Column(fc, 6)};
    const Point normal = Column(fc, 9);
    const Point across[3] = {Column(fc, 12), Column(fc, 15), Column(fc, 18)};
    // M's corners from F's plane; which are within the tolerance, and
    // which edges have both ends beyond it on one side.
    V result = hn::Zero(d);
    M above[3], below[3];
    for (int i = 0; i < 3; ++i) {
      const V off = Dot(normal, Minus(m[i], f[0]));
      result = hn::Add(result, Bit(d, hn::Not(hn::Gt(hn::Abs(off), tol)), 1 << i));
      above[i] = hn::Gt(off, tol);
      below[i] = hn::Lt(off, neg_tol);
    }
    M any_edge_near = hn::FirstN(d, 0);
    for (int i = 0; i < 3; ++i) {
      const int k = (i + 1) % 3;
      const M near = hn::Not(hn::Or(hn::And(above[i], above[k]), hn::And(below[i], below[k])));
      result = hn::Add(result, Bit(d, near, 8 << i));
      any_edge_near = hn::Or(any_edge_near, near);
    }
    // F's corners in M's box grown by the slack.
    const V lo_x = hn::Sub(MinOf(MinOf(m[0].x, m[1].x), m[2].x), slack);
    const V lo_y = hn::Sub(MinOf(MinOf(m[0].y, m[1].y), m[2].y), slack);
    const V lo_z = hn::Sub(MinOf(MinOf(m[0].z, m[1].z), m[2].z), slack);
    const V hi_x = hn::Add(MaxOf(MaxOf(m[0].x, m[1].x), m[2].x), slack);
    const V hi_y = hn::Add(MaxOf(MaxOf(m[0].y, m[1].y), m[2].y), slack);
    const V hi_z = hn::Add(MaxOf(MaxOf(m[0].z, m[1].z), m[2].z), slack);
    for (int j = 0; j < 3; ++j) {
      const M inside = hn::And(
          hn::And(hn::And(hn::Ge(f[j].x, lo_x), hn::Ge(f[j].y, lo_y)), hn::Ge(f[j].z, lo_z)),
          hn::And(hn::And(hn::Le(f[j].x, hi_x), hn::Le(f[j].y, hi_y)), hn::Le(f[j].z, hi_z)));
      result = hn::Add(result, Bit(d, inside, 64 << j));
    }
    // F's edges M's face does not lie beside: beside, every corner is more
    // than twice the tolerance on one side (a NaN distance on neither,
    // wherever it is among the three).
    for (int j = 0; j < 3; ++j) {
      const V d0 = Dot(across[j], Minus(m[0], f[j]));
      const V d1 = Dot(across[j], Minus(m[1], f[j]));
      const V d2 = Dot(across[j], Minus(m[2], f[j]));
      const M beside = hn::Or(
          hn::And(hn::And(hn::Gt(d0, twice_tol), hn::Gt(d1, twice_tol)), hn::Gt(d2, twice_tol)),
          hn::And(hn::And(hn::Lt(d0, neg_twice_tol), hn::Lt(d1, neg_twice_tol)),
                  hn::Lt(d2, neg_twice_tol)));
      result = hn::Add(result, Bit(d, hn::AndNot(beside, any_edge_near), 512 << j));
    }
    hn::Store(result, d, bits);
    for (size_t j = 0; j < count; ++j) {
      const auto b = static_cast<unsigned>(bits[j]);
      out[first + j] = {.moving_corners = static_cast<uint8_t>(b & 7),
                        .moving_edges = static_cast<uint8_t>(b >> 3 & 7),
                        .fixed_corners = static_cast<uint8_t>(b >> 6 & 7),
                        .fixed_edges = static_cast<uint8_t>(b >> 9 & 7)};
    }
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace hs
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace hs {

Vector3d UnitNormal(const Triangle3d& t) {
  const Vector3d n = (t[1] - t[0]).cross(t[2] - t[0]);
  return n.squaredNorm() > 0 ? n.normalized() : Vector3d::Zero();
}

FaceEdges::FaceEdges(const Triangle3d& corners) {
  for (int i = 0; i < 3; ++i) {
    const Vector3d &p = corners[i], &q = corners[(i + 1) % 3];
    along[i] = q - p;
    for (int d = 0; d < 3; ++d) {
      lo[i][d] = std::min(p[d], q[d]);
      hi[i][d] = std::max(p[d], q[d]);
    }
  }
}

FixedFaceEdges::FixedFaceEdges(const Triangle3d& corners)
    : corners(corners), unit_normal(UnitNormal(corners)), edges(corners) {
  for (int i = 0; i < 3; ++i) {
    const Vector3d a = unit_normal.cross(edges.along[i]);
    across[i] = a.squaredNorm() > 0 ? a.normalized() : Vector3d::Zero();
  }
}

HWY_EXPORT(NearFeaturesLanes);

void NearFeaturesBatch(const MovingFaceCorners* moving, const FixedFaceEdges* fixed,
                       std::span<const FaceRecordPair> pairs, double tolerance, double corner_slack,
                       std::span<NearFeatures> out) {
  HWY_DYNAMIC_DISPATCH(NearFeaturesLanes)
  (moving, fixed, pairs.data(), pairs.size(), tolerance, corner_slack, out.data());
}

}  // namespace hs
#endif

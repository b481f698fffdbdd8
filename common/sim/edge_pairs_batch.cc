// EdgeLinesMayMeet over a batch of object edges (edge_pairs_batch.h):
// written by hand with Google Highway because no library does this test,
// and it must give the scalar test's answers. Every operation is the
// scalar one (edge_pairs.cc's LinesOf) in the scalar order: no fused
// multiply-add (the build compiles both files with -ffp-contract=off),
// std::max as its comparison, Eigen's cross and dot products in their
// order (common/collision/scalar_order-inl.h). The object edges are
// gathered from their columns by row.

#include "common/sim/edge_pairs_batch.h"

#include <algorithm>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "common/sim/edge_pairs_batch.cc"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"
// After highway.h: compiled for each target.
#include "common/collision/scalar_order-inl.h"

#ifndef HS_SIM_EDGE_PAIRS_BATCH_TOOL_EDGE_
#define HS_SIM_EDGE_PAIRS_BATCH_TOOL_EDGE_
namespace hs {
// The tool edge and the move, as the scalar test takes them; one type for
// every target.
struct BatchToolEdge {
  double from[3], along[3], length, along_sq;
  double parallel_sine;  // 4 turn + 1e-6
  double slide_margin;   // (3 or 1) margin
  double lines_m;
  bool lines_tested;  // with a margin
};
}  // namespace hs
#endif

HWY_BEFORE_NAMESPACE();
namespace hs {
namespace HWY_NAMESPACE {

size_t EdgeLinesMayMeetLanes(const BatchToolEdge& t, const double* const* columns,
                             const int* candidates, size_t n, int* kept) {
  const D d;
  const hn::RebindToSigned<D> di;
  const hn::Rebind<int32_t, D> d32;
  const size_t lanes = hn::Lanes(d);
  constexpr size_t kMaxLanes = HWY_MAX_BYTES / sizeof(double);
  HWY_ALIGN int32_t rows[kMaxLanes];
  HWY_ALIGN double keep[kMaxLanes];
  const V ux = hn::Set(d, t.along[0]), uy = hn::Set(d, t.along[1]), uz = hn::Set(d, t.along[2]);
  const V lu = hn::Set(d, t.length), uu = hn::Set(d, t.along_sq);
  const V one = hn::Set(d, 1.0);
  size_t out = 0;
  for (size_t first = 0; first < n; first += lanes) {
    const size_t count = std::min(lanes, n - first);
    for (size_t j = 0; j < lanes; ++j) rows[j] = candidates[first + std::min(j, count - 1)];
    const auto row = hn::PromoteTo(di, hn::Load(d32, rows));
    auto gather = [&](EdgeColumns::Column c) { return hn::GatherIndex(d, columns[c], row); };
    const V vx = gather(EdgeColumns::kAlongX), vy = gather(EdgeColumns::kAlongY),
            vz = gather(EdgeColumns::kAlongZ), lv = gather(EdgeColumns::kLength);
    // n = u x v, its length, the sine of the angle.
    const V nx = hn::Sub(hn::Mul(uy, vz), hn::Mul(uz, vy));
    const V ny = hn::Sub(hn::Mul(uz, vx), hn::Mul(ux, vz));
    const V nz = hn::Sub(hn::Mul(ux, vy), hn::Mul(uy, vx));
    const V length = hn::Sqrt(Dot(nx, ny, nz, nx, ny, nz));
    const V sine = hn::Div(length, hn::Mul(lu, lv));
    const M near_parallel = hn::Not(hn::Gt(sine, hn::Set(d, t.parallel_sine)));
    // w = t_from - o_from.
    const V wx = hn::Sub(hn::Set(d, t.from[0]), gather(EdgeColumns::kFromX));
    const V wy = hn::Sub(hn::Set(d, t.from[1]), gather(EdgeColumns::kFromY));
    const V wz = hn::Sub(hn::Set(d, t.from[2]), gather(EdgeColumns::kFromZ));
    M apart = hn::FirstN(d, 0);
    if (t.lines_tested) {
      apart = hn::Gt(hn::Abs(Dot(nx, ny, nz, wx, wy, wz)), hn::Mul(hn::Set(d, t.lines_m), length));
    }
    // The lines' closest points, and how far past the ends they may fall.
    const V uv = Dot(ux, uy, uz, vx, vy, vz), vv = Dot(vx, vy, vz, vx, vy, vz);
    const V uw = Dot(ux, uy, uz, wx, wy, wz), vw = Dot(vx, vy, vz, wx, wy, wz);
    const V det = hn::Sub(hn::Mul(uu, vv), hn::Mul(uv, uv));
    const V a = hn::Div(hn::Sub(hn::Mul(uv, vw), hn::Mul(vv, uw)), det);
    const V b = hn::Div(hn::Sub(hn::Mul(uu, vw), hn::Mul(uv, uw)), det);
    const V slide = hn::Add(hn::Div(hn::Set(d, t.slide_margin), sine),
                            hn::Mul(hn::Set(d, 1e-9), hn::Add(lu, lv)));
    const V ends = hn::Set(d, 2e-9);
    const V past_u = MaxOf(hn::Div(slide, lu), ends), past_v = MaxOf(hn::Div(slide, lv), ends);
    apart = hn::Or(apart, hn::Or(hn::Lt(a, hn::Neg(past_u)), hn::Gt(a, hn::Add(one, past_u))));
    apart = hn::Or(apart, hn::Or(hn::Lt(b, hn::Neg(past_v)), hn::Gt(b, hn::Add(one, past_v))));
    const M may_meet = hn::Or(near_parallel, hn::Not(apart));
    hn::Store(hn::IfThenElseZero(may_meet, one), d, keep);
    for (size_t j = 0; j < count; ++j) {
      if (keep[j] != 0) kept[out++] = candidates[first + j];
    }
  }
  return out;
}

}  // namespace HWY_NAMESPACE
}  // namespace hs
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace hs {

HWY_EXPORT(EdgeLinesMayMeetLanes);

void EdgeColumns::Clear() {
  for (std::vector<double>& column : columns_) column.clear();
}

void EdgeColumns::Add(const WorldEdge& e, double length_m) {
  const Vector3d along = e.to - e.from;
  for (int i = 0; i < 3; ++i) {
    columns_[kFromX + i].push_back(e.from[i]);
    columns_[kAlongX + i].push_back(along[i]);
  }
  columns_[kLength].push_back(length_m);
}

size_t KeepEdgesWhoseLinesMayMeet(const Vector3d& t_from, const Vector3d& u, double lu,
                                  const EdgeColumns& edges, std::span<const int> candidates,
                                  const EdgeMove& move, int* kept) {
  // The scalar test's constants, computed as it computes them.
  const BatchToolEdge tool{.from = {t_from.x(), t_from.y(), t_from.z()},
                           .along = {u.x(), u.y(), u.z()},
                           .length = lu,
                           .along_sq = u.dot(u),
                           .parallel_sine = 4 * move.turn + 1e-6,
                           .slide_margin = (move.turn > 0 ? 3 : 1) * move.margin_m,
                           .lines_m = move.lines_m,
                           .lines_tested = move.margin_m > 0};
  std::array<const double*, EdgeColumns::kNumColumns> columns;
  for (int c = 0; c < EdgeColumns::kNumColumns; ++c) {
    columns[c] = edges.column(static_cast<EdgeColumns::Column>(c));
  }
  return HWY_DYNAMIC_DISPATCH(EdgeLinesMayMeetLanes)(tool, columns.data(), candidates.data(),
                                                     candidates.size(), kept);
}

}  // namespace hs
#endif

// QuickTrianglesTest over several face pairs at once (face_test_batch.h):
// written by hand with Google Highway because no library does this test,
// and it must give the scalar test's answer and gap bit for bit. Every
// operation is the scalar one in the scalar order: no fused multiply-add
// (the build compiles this file with -ffp-contract=off), std::min and
// std::max as their comparisons, the scalar's branches and corner choices
// as lane masks (scalar_order-inl.h, shared with plane_bounds_batch.cc).
// The faces are copied from the callers' arrays into lanes.

#include "common/collision/face_test_batch.h"

#include <algorithm>

#include "common/collision/placed_faces.h"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "common/collision/face_test_batch.cc"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"
// After highway.h: compiled for each target.
#include "common/collision/scalar_order-inl.h"

HWY_BEFORE_NAMESPACE();
namespace hs {
namespace HWY_NAMESPACE {

// A PlacedFace as doubles: corners 0-8, normal 9-11, then its box.
constexpr int64_t kFaceDoubles = sizeof(PlacedFace) / sizeof(double);
static_assert(sizeof(PlacedFace) == 18 * sizeof(double), "a PlacedFace is 18 packed doubles");

struct Point {
  V x, y, z;
};
// The faces of one batch, a lane each: corners and TriangleNormal.
struct Faces {
  Point corner[3];
  Point normal;
};

Point Minus(const Point& p, const Point& q) {
  return {hn::Sub(p.x, q.x), hn::Sub(p.y, q.y), hn::Sub(p.z, q.z)};
}
V Dot(const Point& p, const Point& q) { return Dot(p.x, p.y, p.z, q.x, q.y, q.z); }
Point Cross(const Point& p, const Point& q) {
  return {hn::Sub(hn::Mul(p.y, q.z), hn::Mul(p.z, q.y)),
          hn::Sub(hn::Mul(p.z, q.x), hn::Mul(p.x, q.z)),
          hn::Sub(hn::Mul(p.x, q.y), hn::Mul(p.y, q.x))};
}
V Pick(M m, V yes, V no) { return hn::IfThenElse(m, yes, no); }

// Which of LoadFaces' `offsets` lands in lane `lane`: its own, but on
// AVX3, whose block shuffles leave rows 2-3 and 4-5 swapped.
size_t RowOfLane(size_t lane) {
#if HWY_TARGET == HWY_AVX3
  constexpr size_t kRow[8] = {0, 1, 4, 5, 2, 3, 6, 7};
  return kRow[lane];
#else
  return lane;
#endif
}

// Loads the faces at `offsets` (in doubles from `base`), face
// `offsets[RowOfLane(j)]` in lane j. On AVX2 and AVX3, the faces' corners
// and normals (12 doubles each) are loaded in rows of four and transposed
// in registers; elsewhere they are copied through `soa` (12 rows of
// `stride`) a double at a time. (On this project's machine, an AMD EPYC,
// gathers a coordinate at a time took about as many instructions as the
// transpose but more time, and the copy more of both: its vector loads
// wait for the stores before them.)
Faces LoadFaces(D d, const double* base, const int64_t* offsets, double* soa, size_t stride) {
  V column[12];
#if HWY_TARGET == HWY_AVX2 || HWY_TARGET == HWY_AVX3
  (void)soa;
  (void)stride;
  for (int m = 0; m < 3; ++m) {
    // Row j: doubles 4m to 4m + 3 of face j (AVX2), of faces j and j + 4
    // in the two halves (AVX3).
    V row[4];
#if HWY_TARGET == HWY_AVX2
    for (int j = 0; j < 4; ++j) row[j] = hn::LoadU(d, base + offsets[j] + 4 * m);
#else
    const hn::Half<D> half;
    for (int j = 0; j < 4; ++j) {
      row[j] = hn::Combine(d, hn::LoadU(half, base + offsets[j + 4] + 4 * m),
                           hn::LoadU(half, base + offsets[j] + 4 * m));
    }
#endif
    // t0 = (r0[0] r1[0] r0[2] r1[2]), t1 = (r0[1] r1[1] r0[3] r1[3]); t2, t3
    // of r2 and r3 (in each half, on AVX3); then each column k gathers
    // element k of the rows.
    const V t0 = hn::InterleaveLower(d, row[0], row[1]);
    const V t1 = hn::InterleaveUpper(d, row[0], row[1]);
    const V t2 = hn::InterleaveLower(d, row[2], row[3]);
    const V t3 = hn::InterleaveUpper(d, row[2], row[3]);
#if HWY_TARGET == HWY_AVX2
    column[4 * m] = hn::ConcatLowerLower(d, t2, t0);
    column[4 * m + 1] = hn::ConcatLowerLower(d, t3, t1);
    column[4 * m + 2] = hn::ConcatUpperUpper(d, t2, t0);
    column[4 * m + 3] = hn::ConcatUpperUpper(d, t3, t1);
#else
    // 128-bit blocks 0 and 2 of t0, then of t2 (rows 0 1 4 5 2 3 6 7); 1
    // and 3 for the odd elements. Highway 1.0 has no such shuffle of two
    // vectors' blocks.
    constexpr int kEven = _MM_SHUFFLE(2, 0, 2, 0), kOdd = _MM_SHUFFLE(3, 1, 3, 1);
    column[4 * m] = V{_mm512_shuffle_f64x2(t0.raw, t2.raw, kEven)};
    column[4 * m + 1] = V{_mm512_shuffle_f64x2(t1.raw, t3.raw, kEven)};
    column[4 * m + 2] = V{_mm512_shuffle_f64x2(t0.raw, t2.raw, kOdd)};
    column[4 * m + 3] = V{_mm512_shuffle_f64x2(t1.raw, t3.raw, kOdd)};
#endif
  }
#else
  const size_t lanes = hn::Lanes(d);
  for (size_t j = 0; j < lanes; ++j) {
    const double* face = base + offsets[j];
    for (int k = 0; k < 12; ++k) soa[k * stride + j] = face[k];
  }
  for (int k = 0; k < 12; ++k) column[k] = hn::Load(d, soa + k * stride);
#endif
  Faces f;
  for (int k = 0; k < 4; ++k) {
    Point& p = k < 3 ? f.corner[k] : f.normal;
    p = {column[3 * k], column[3 * k + 1], column[3 * k + 2]};
  }
  return f;
}

// The corners' distances `dist` from a plane whose normal has squared
// length `norm_sq`: whether they lie beyond the margin on one side
// (BeyondPlane), and how far (PlaneGap).
struct PlaneSide {
  M beyond;
  V gap;
};
PlaneSide Side(D d, const V (&dist)[3], V norm_sq, double margin) {
  const V zero = hn::Zero(d);
  const V lo = MinOf(MinOf(dist[0], dist[1]), dist[2]);
  const V hi = MaxOf(MaxOf(dist[0], dist[1]), dist[2]);
  const V gap = MaxOf(hn::Sub(lo, zero), hn::Sub(zero, hi));
  const M separated = hn::And(
      hn::Gt(gap, zero), hn::Gt(hn::Mul(gap, gap), hn::Mul(hn::Set(d, margin * margin), norm_sq)));
  return {hn::And(hn::Ne(norm_sq, zero), separated),
          hn::Sub(hn::Div(MaxOf(lo, hn::Neg(hi)), hn::Sqrt(norm_sq)), hn::Set(d, margin))};
}

// CrossingOnLine: where the faces `t` cross the other's plane, along
// `line`, as [lo, hi]; `valid` where the scalar finds a crossing.
void CrossingOnLine(D d, const Faces& t, const V (&dist)[3], V clear_sq, const Point& line,
                    const Point& origin, M& valid, V& lo, V& hi) {
  const V zero = hn::Zero(d);
  M clear = hn::Gt(hn::Mul(dist[0], dist[0]), clear_sq);
  clear = hn::And(clear, hn::Gt(hn::Mul(dist[1], dist[1]), clear_sq));
  clear = hn::And(clear, hn::Gt(hn::Mul(dist[2], dist[2]), clear_sq));
  const M above[3] = {hn::Gt(dist[0], zero), hn::Gt(dist[1], zero), hn::Gt(dist[2], zero)};
  const M same01 = hn::Not(hn::Xor(above[0], above[1]));
  const M same02 = hn::Not(hn::Xor(above[0], above[2]));
  const M same12 = hn::Not(hn::Xor(above[1], above[2]));
  valid = hn::AndNot(hn::And(same01, same12), clear);
  // The corner alone on its side: 2 where 0 and 1 agree, else 1 where 0
  // and 2 do, else 0; then `next` and `last` after it in turn.
  const M lone2 = same01, lone1 = hn::AndNot(same01, same02);
  V at[3];
  for (int k = 0; k < 3; ++k) at[k] = Dot(line, Minus(t.corner[k], origin));
  const auto choose = [&](const V(&x)[3], int if0, int if1, int if2) {
    return Pick(lone2, x[if2], Pick(lone1, x[if1], x[if0]));
  };
  const V at_lone = choose(at, 0, 1, 2), at_next = choose(at, 1, 2, 0),
          at_last = choose(at, 2, 0, 1);
  const V d_lone = choose(dist, 0, 1, 2), d_next = choose(dist, 1, 2, 0),
          d_last = choose(dist, 2, 0, 1);
  const V end_next = hn::Add(
      at_next, hn::Div(hn::Mul(hn::Sub(at_lone, at_next), d_next), hn::Sub(d_next, d_lone)));
  const V end_last = hn::Add(
      at_last, hn::Div(hn::Mul(hn::Sub(at_lone, at_last), d_last), hn::Sub(d_last, d_lone)));
  const M in_order = hn::Le(end_next, end_last);
  lo = Pick(in_order, end_next, end_last);
  hi = Pick(in_order, end_last, end_next);
}

// CrossingTest's fast answer kYes, given the corners' distances from the
// other's plane.
M ClearlyCross(D d, const Faces& a, const V (&da)[3], V na_sq, const Faces& b, const V (&db)[3],
               V nb_sq) {
  const V zero = hn::Zero(d);
  const Point ab = Minus(a.corner[0], b.corner[0]);
  const Point a1 = Minus(a.corner[1], a.corner[0]), a2 = Minus(a.corner[2], a.corner[0]);
  const Point b1 = Minus(b.corner[1], b.corner[0]), b2 = Minus(b.corner[2], b.corner[0]);
  const V sum = hn::Add(
      hn::Add(hn::Add(hn::Add(Dot(ab, ab), Dot(a1, a1)), Dot(a2, a2)), Dot(b1, b1)), Dot(b2, b2));
  const V size_sq = hn::Mul(hn::Set(d, 5.0), sum);
  const V clear_sq = hn::Mul(hn::Set(d, kClearlyRelative * kClearlyRelative), size_sq);
  const Point line = Cross(a.normal, b.normal);
  const V line_sq = Dot(line, line);
  M valid_a, valid_b;
  V lo_a, hi_a, lo_b, hi_b;
  CrossingOnLine(d, a, da, hn::Mul(clear_sq, nb_sq), line, b.corner[0], valid_a, lo_a, hi_a);
  CrossingOnLine(d, b, db, hn::Mul(clear_sq, na_sq), line, b.corner[0], valid_b, lo_b, hi_b);
  const V overlap = hn::Sub(MinOf(hi_a, hi_b), MaxOf(lo_a, lo_b));
  M yes = hn::And(hn::Gt(line_sq, zero), hn::And(valid_a, valid_b));
  yes = hn::And(yes, hn::Gt(overlap, zero));
  return hn::And(yes, hn::Gt(hn::Mul(overlap, overlap), hn::Mul(clear_sq, line_sq)));
}

// One batch: the answer (QuickTriangleTest::Answer as a double) and gap.
void Quick(D d, const Faces& a, const Faces& b, double margin, V& answer, V& gap) {
  V db[3], da[3];
  for (int k = 0; k < 3; ++k) {
    db[k] = Dot(a.normal, Minus(b.corner[k], a.corner[0]));
    da[k] = Dot(b.normal, Minus(a.corner[k], b.corner[0]));
  }
  const V na_sq = Dot(a.normal, a.normal), nb_sq = Dot(b.normal, b.normal);
  const PlaneSide side_a = Side(d, db, na_sq, margin), side_b = Side(d, da, nb_sq, margin);
  const M meet = ClearlyCross(d, a, da, na_sq, b, db, nb_sq);
  using Answer = QuickTriangleTest::Answer;
  const V apart = hn::Set(d, static_cast<double>(Answer::kApart));
  answer = Pick(hn::Or(side_a.beyond, side_b.beyond), apart,
                hn::IfThenElseZero(meet, hn::Set(d, static_cast<double>(Answer::kMeet))));
  gap = Pick(side_a.beyond, side_a.gap, hn::IfThenElseZero(side_b.beyond, side_b.gap));
}

void QuickLanes(const PlacedFace* faces_a, const PlacedFace* faces_b, const TrianglePair* pairs,
                size_t n, double margin, QuickTriangleTest* out) {
  const D d;
  const size_t lanes = hn::Lanes(d);
  constexpr size_t kMaxLanes = HWY_MAX_BYTES / sizeof(double);
  HWY_ALIGN int64_t offset_a[kMaxLanes], offset_b[kMaxLanes];
  HWY_ALIGN double answers[kMaxLanes], gaps[kMaxLanes];
  HWY_ALIGN double soa[12 * kMaxLanes];
  const auto* base_a = reinterpret_cast<const double*>(faces_a);
  const auto* base_b = reinterpret_cast<const double*>(faces_b);
  for (size_t first = 0; first < n; first += lanes) {
    const size_t count = std::min(lanes, n - first);
    for (size_t j = 0; j < lanes; ++j) {  // a short last batch repeats its last pair
      const size_t i = first + std::min(j, count - 1);
      offset_a[RowOfLane(j)] = pairs[i].a * kFaceDoubles;
      offset_b[RowOfLane(j)] = pairs[i].b * kFaceDoubles;
    }
    const Faces a = LoadFaces(d, base_a, offset_a, soa, kMaxLanes);
    const Faces b = LoadFaces(d, base_b, offset_b, soa, kMaxLanes);
    V answer, gap;
    Quick(d, a, b, margin, answer, gap);
    hn::Store(answer, d, answers);
    hn::Store(gap, d, gaps);
    for (size_t j = 0; j < count; ++j) {
      out[first + j] = {static_cast<QuickTriangleTest::Answer>(static_cast<int>(answers[j])),
                        gaps[j]};
    }
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace hs
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace hs {

HWY_EXPORT(QuickLanes);

void QuickTrianglesTestBatch(const PlacedFace* faces_a, const PlacedFace* faces_b,
                             std::span<const TrianglePair> pairs, double margin,
                             std::span<QuickTriangleTest> out) {
  HWY_DYNAMIC_DISPATCH(QuickLanes)
  (faces_a, faces_b, pairs.data(), pairs.size(), margin, out.data());
}

}  // namespace hs
#endif

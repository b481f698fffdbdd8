// QuickTrianglesTest over several face pairs at once (face_test_batch.h):
// written by hand with Google Highway because no library does this test,
// and it must give the scalar test's answer, gap and edge pair bit for bit. Every
// operation is the scalar one in the scalar order: no fused multiply-add
// (the build compiles this file with -ffp-contract=off), std::min and
// std::max as their comparisons, the scalar's branches and corner choices
// as lane masks (scalar_order-inl.h, shared with plane_bounds_batch.cc).
// The faces are loaded from the callers' arrays into lanes
// (lane_rows-inl.h).

#include "common/collision/face_test_batch.h"

#include <algorithm>

#include "common/collision/placed_faces.h"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "common/collision/face_test_batch.cc"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"
// After highway.h: compiled for each target.
#include "common/collision/lane_rows-inl.h"
#include "common/collision/scalar_order-inl.h"

HWY_BEFORE_NAMESPACE();
namespace hs {
namespace HWY_NAMESPACE {

// A PlacedFace as doubles: corners 0-8, normal 9-11, then its box.
constexpr int64_t kFaceDoubles = sizeof(PlacedFace) / sizeof(double);
static_assert(sizeof(PlacedFace) == 18 * sizeof(double), "a PlacedFace is 18 packed doubles");

// The faces of one batch, a lane each: corners and TriangleNormal.
struct Faces {
  Point corner[3];
  Point normal;
};

V Pick(M m, V yes, V no) { return hn::IfThenElse(m, yes, no); }

// Loads the faces at `offsets` (in doubles from `base`), face
// `offsets[RowOfLane(j)]` in lane j: their corners and normals, the first
// 12 doubles (lane_rows-inl.h).
HWY_INLINE Faces LoadFaces(D d, const double* base, const int64_t* offsets, double* soa,
                           size_t stride) {
  V column[12];
  LoadColumns<3>(d, base, offsets, soa, stride, column);
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
HWY_INLINE PlaneSide Side(D d, const V (&dist)[3], V norm_sq, double margin) {
  const V zero = hn::Zero(d);
  const V lo = MinOf(MinOf(dist[0], dist[1]), dist[2]);
  const V hi = MaxOf(MaxOf(dist[0], dist[1]), dist[2]);
  const V gap = MaxOf(hn::Sub(lo, zero), hn::Sub(zero, hi));
  const M separated = hn::And(
      hn::Gt(gap, zero), hn::Gt(hn::Mul(gap, gap), hn::Mul(hn::Set(d, margin * margin), norm_sq)));
  return {hn::And(hn::Ne(norm_sq, zero), separated),
          hn::Sub(hn::Div(MaxOf(lo, hn::Neg(hi)), hn::Sqrt(norm_sq)), hn::Set(d, margin))};
}

// CrossingOnLine's answer: where the faces cross the other's plane,
// along the line, as [lo, hi]; `valid` where the scalar finds a crossing;
// which corner is alone on its side (2 where `lone2`, else 1 where
// `lone1`, else 0), and whether the end from the edge after it comes
// first (`in_order`).
struct LineCrossing {
  M valid;
  V lo, hi;
  M lone2, lone1, in_order;
};

// CrossingOnLine: where the faces `t` cross the other's plane, along
// `line`, given their corners' distances `dist` from it.
HWY_INLINE LineCrossing CrossingOnLine(D d, const Faces& t, const V (&dist)[3], V clear_sq,
                                       const Point& line, const Point& origin) {
  const V zero = hn::Zero(d);
  M clear = hn::Gt(hn::Mul(dist[0], dist[0]), clear_sq);
  clear = hn::And(clear, hn::Gt(hn::Mul(dist[1], dist[1]), clear_sq));
  clear = hn::And(clear, hn::Gt(hn::Mul(dist[2], dist[2]), clear_sq));
  const M above[3] = {hn::Gt(dist[0], zero), hn::Gt(dist[1], zero), hn::Gt(dist[2], zero)};
  const M same01 = hn::Not(hn::Xor(above[0], above[1]));
  const M same02 = hn::Not(hn::Xor(above[0], above[2]));
  const M same12 = hn::Not(hn::Xor(above[1], above[2]));
  LineCrossing out;
  out.valid = hn::AndNot(hn::And(same01, same12), clear);
  // The corner alone on its side: 2 where 0 and 1 agree, else 1 where 0
  // and 2 do, else 0; then `next` and `last` after it in turn.
  out.lone2 = same01;
  out.lone1 = hn::AndNot(same01, same02);
  V at[3];
  for (int k = 0; k < 3; ++k) at[k] = Dot(line, Minus(t.corner[k], origin));
  const auto choose = [&](const V(&x)[3], int if0, int if1, int if2) {
    return Pick(out.lone2, x[if2], Pick(out.lone1, x[if1], x[if0]));
  };
  const V at_lone = choose(at, 0, 1, 2), at_next = choose(at, 1, 2, 0),
          at_last = choose(at, 2, 0, 1);
  const V d_lone = choose(dist, 0, 1, 2), d_next = choose(dist, 1, 2, 0),
          d_last = choose(dist, 2, 0, 1);
  const V end_next = hn::Add(
      at_next, hn::Div(hn::Mul(hn::Sub(at_lone, at_next), d_next), hn::Sub(d_next, d_lone)));
  const V end_last = hn::Add(
      at_last, hn::Div(hn::Mul(hn::Sub(at_lone, at_last), d_last), hn::Sub(d_last, d_lone)));
  out.in_order = hn::Le(end_next, end_last);
  out.lo = Pick(out.in_order, end_next, end_last);
  out.hi = Pick(out.in_order, end_last, end_next);
  return out;
}

// The edge of the faces `t` that gives the end of their crossing `c`
// facing the other's (the high end where `high`), as the scalar's
// LineCrossing holds it: edge `lone` from the lone corner to the next, or
// edge `last` from the lone corner to the last; its number in `index`.
HWY_INLINE Point FacingEdge(D d, const Faces& t, const LineCrossing& c, M high, V& index) {
  // The high end comes from edge `last` when in order, the low end from
  // edge `lone`.
  const M use_last = hn::Not(hn::Xor(c.in_order, high));
  const M lone0 = hn::Not(hn::Or(c.lone2, c.lone1));
  // The edge's far corner: `last` is 2, 0, 1 and `next` 1, 2, 0 for a lone
  // corner 0, 1, 2.
  const M far0 = hn::Or(hn::And(c.lone1, use_last), hn::AndNot(use_last, c.lone2));
  const M far1 = hn::Or(hn::AndNot(use_last, lone0), hn::And(c.lone2, use_last));
  const auto corner = [&](M is2, M is1, V Point::*x) {
    return Pick(is2, t.corner[2].*x, Pick(is1, t.corner[1].*x, t.corner[0].*x));
  };
  const M far2 = hn::Not(hn::Or(far0, far1));
  const Point lone{corner(c.lone2, c.lone1, &Point::x), corner(c.lone2, c.lone1, &Point::y),
                   corner(c.lone2, c.lone1, &Point::z)};
  const Point far{corner(far2, far1, &Point::x), corner(far2, far1, &Point::y),
                  corner(far2, far1, &Point::z)};
  const V lone_index = Pick(c.lone2, hn::Set(d, 2.0), hn::IfThenElseZero(c.lone1, hn::Set(d, 1.0)));
  const V last_index = Pick(c.lone2, hn::Set(d, 1.0), hn::IfThenZeroElse(c.lone1, hn::Set(d, 2.0)));
  index = Pick(use_last, last_index, lone_index);
  return Minus(far, lone);
}

// ProjectThree: the extent of the faces `t` along `axis`.
HWY_INLINE void Project(const Point& axis, const Faces& t, V& lo, V& hi) {
  const V x = Dot(axis, t.corner[0]), y = Dot(axis, t.corner[1]), z = Dot(axis, t.corner[2]);
  lo = MinOf(MinOf(x, y), z);
  hi = MaxOf(MaxOf(x, y), z);
}

// The line where the planes meet, and where each batch's faces cross it
// (CrossingTest's start).
struct Crossings {
  V clear_sq, line_sq;
  LineCrossing on_a, on_b;
  V overlap;  // of the two on the line
  M valid;    // where the scalar finds both crossings on a line
};
HWY_INLINE Crossings CrossTheLine(D d, const Faces& a, const V (&da)[3], V na_sq, const Faces& b,
                                  const V (&db)[3], V nb_sq) {
  const Point ab = Minus(a.corner[0], b.corner[0]);
  const Point a1 = Minus(a.corner[1], a.corner[0]), a2 = Minus(a.corner[2], a.corner[0]);
  const Point b1 = Minus(b.corner[1], b.corner[0]), b2 = Minus(b.corner[2], b.corner[0]);
  const V sum = hn::Add(
      hn::Add(hn::Add(hn::Add(Dot(ab, ab), Dot(a1, a1)), Dot(a2, a2)), Dot(b1, b1)), Dot(b2, b2));
  const V size_sq = hn::Mul(hn::Set(d, 5.0), sum);
  Crossings c;
  c.clear_sq = hn::Mul(hn::Set(d, kClearlyRelative * kClearlyRelative), size_sq);
  const Point line = Cross(a.normal, b.normal);
  c.line_sq = Dot(line, line);
  c.on_a = CrossingOnLine(d, a, da, hn::Mul(c.clear_sq, nb_sq), line, b.corner[0]);
  c.on_b = CrossingOnLine(d, b, db, hn::Mul(c.clear_sq, na_sq), line, b.corner[0]);
  c.overlap = hn::Sub(MinOf(c.on_a.hi, c.on_b.hi), MaxOf(c.on_a.lo, c.on_b.lo));
  c.valid = hn::And(hn::Gt(c.line_sq, hn::Zero(d)), hn::And(c.on_a.valid, c.on_b.valid));
  return c;
}

// CrossingTest's kYes: the crossings overlap clearly.
HWY_INLINE M ClearlyCross(D d, const Crossings& c) {
  const M overlap = hn::And(c.valid, hn::Gt(c.overlap, hn::Zero(d)));
  return hn::And(overlap, hn::Gt(hn::Mul(c.overlap, c.overlap), hn::Mul(c.clear_sq, c.line_sq)));
}

// CrossingTest's kApart: the crossings are apart (not overlap >= 0, NaN
// included), and the cross of the edges that give their facing ends keeps
// the faces beyond `margin`; that edge pair's number in `edge_pair`.
HWY_INLINE M EdgesApart(D d, const Faces& a, const Faces& b, const Crossings& c, double margin,
                        V& edge_pair) {
  const V zero = hn::Zero(d);
  const M a_first = hn::Lt(c.on_a.hi, c.on_b.lo);
  V index_a, index_b;
  const Point edge_a = FacingEdge(d, a, c.on_a, a_first, index_a);
  const Point edge_b = FacingEdge(d, b, c.on_b, hn::Not(a_first), index_b);
  edge_pair = hn::Add(hn::Mul(hn::Set(d, 3.0), index_a), index_b);
  const Point axis = Cross(edge_a, edge_b);
  const V axis_sq = Dot(axis, axis);
  const V floor_sq = hn::Mul(hn::Set(d, kAxisRelativeFloor * kAxisRelativeFloor),
                             hn::Mul(Dot(edge_a, edge_a), Dot(edge_b, edge_b)));
  V a_lo, a_hi, b_lo, b_hi;
  Project(axis, a, a_lo, a_hi);
  Project(axis, b, b_lo, b_hi);
  const V gap = MaxOf(hn::Sub(a_lo, b_hi), hn::Sub(b_lo, a_hi));
  const M separated = hn::And(
      hn::Gt(gap, zero), hn::Gt(hn::Mul(gap, gap), hn::Mul(hn::Set(d, margin * margin), axis_sq)));
  const M apart = hn::AndNot(hn::Ge(c.overlap, zero), c.valid);
  return hn::And(apart, hn::And(hn::Gt(axis_sq, floor_sq), separated));
}

// QuickTrianglesTest's last resort, for faces with no crossing to
// compare (CrossTheLine's `valid` false): the first of the nine edge
// crosses, in ForEachAxis's order, that keeps the faces beyond `margin`
// (EdgeCrossSeparates): where one does, its number in `edge_pair`. Stops once
// every lane has one.
HWY_INLINE M FirstEdgeCrossApart(D d, const Faces& a, const Faces& b, double margin, V& edge_pair) {
  const V zero = hn::Zero(d);
  const V margin_sq = hn::Set(d, margin * margin);
  const V floor_sq = hn::Set(d, kAxisRelativeFloor * kAxisRelativeFloor);
  Point edge_a[3], edge_b[3];
  V length_a[3], length_b[3];  // squared
  for (int i = 0; i < 3; ++i) {
    edge_a[i] = Minus(a.corner[(i + 1) % 3], a.corner[i]);
    edge_b[i] = Minus(b.corner[(i + 1) % 3], b.corner[i]);
    length_a[i] = Dot(edge_a[i], edge_a[i]);
    length_b[i] = Dot(edge_b[i], edge_b[i]);
  }
  M found = hn::FirstN(d, 0);
  edge_pair = hn::Set(d, -1.0);
  for (int k = 0; k < 9 && !hn::AllTrue(d, found); ++k) {
    const int i = k / 3, j = k % 3;
    const Point axis = Cross(edge_a[i], edge_b[j]);
    const V norm_sq = Dot(axis, axis);
    const M usable = hn::And(hn::Gt(norm_sq, hn::Mul(floor_sq, hn::Mul(length_a[i], length_b[j]))),
                             hn::Ne(norm_sq, zero));
    // ProjectTwo: an edge's start and the corner off it, on either face.
    const V a_start = Dot(axis, a.corner[i]), a_off = Dot(axis, a.corner[(i + 2) % 3]);
    const V b_start = Dot(axis, b.corner[j]), b_off = Dot(axis, b.corner[(j + 2) % 3]);
    const V gap = MaxOf(hn::Sub(MinOf(a_start, a_off), MaxOf(b_start, b_off)),
                        hn::Sub(MinOf(b_start, b_off), MaxOf(a_start, a_off)));
    const M separated =
        hn::And(hn::Gt(gap, zero), hn::Gt(hn::Mul(gap, gap), hn::Mul(margin_sq, norm_sq)));
    const M first = hn::AndNot(found, hn::And(usable, separated));
    edge_pair = Pick(first, hn::Set(d, static_cast<double>(k)), edge_pair);
    found = hn::Or(found, first);
  }
  return found;
}

// EdgeCrossSeparates of the edge cross `edge_pair` (3 i + j, lane by
// lane): where it keeps the faces beyond `margin`, and its gap and lever
// there (0 elsewhere).
HWY_INLINE M HintedEdgeCross(D d, const Faces& a, const Faces& b, V edge_pair, double margin,
                             V& gap_m, V& lever_m) {
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0), two = hn::Set(d, 2.0);
  // i = edge_pair / 3 and j = edge_pair % 3 as masks; the edge of each
  // face, its start and the corner off it.
  const M i0 = hn::Lt(edge_pair, hn::Set(d, 3.0));
  const M i1 = hn::AndNot(i0, hn::Lt(edge_pair, hn::Set(d, 6.0)));
  const V j = hn::Sub(edge_pair, hn::Mul(hn::Set(d, 3.0), Pick(i0, zero, Pick(i1, one, two))));
  const M j0 = hn::Eq(j, zero), j1 = hn::Eq(j, one);
  const auto corner = [&](const Faces& t, M is0, M is1, int k) {
    const Point& p0 = t.corner[k % 3];
    const Point& p1 = t.corner[(k + 1) % 3];
    const Point& p2 = t.corner[(k + 2) % 3];
    return Point{Pick(is0, p0.x, Pick(is1, p1.x, p2.x)), Pick(is0, p0.y, Pick(is1, p1.y, p2.y)),
                 Pick(is0, p0.z, Pick(is1, p1.z, p2.z))};
  };
  const Point a_start = corner(a, i0, i1, 0), a_end = corner(a, i0, i1, 1),
              a_off = corner(a, i0, i1, 2);
  const Point b_start = corner(b, j0, j1, 0), b_end = corner(b, j0, j1, 1),
              b_off = corner(b, j0, j1, 2);
  const Point ea = Minus(a_end, a_start), eb = Minus(b_end, b_start);
  const V la = Dot(ea, ea), lb = Dot(eb, eb);
  const Point axis = Cross(ea, eb);
  const V norm_sq = Dot(axis, axis);
  const V floor2 = hn::Set(d, kAxisRelativeFloor * kAxisRelativeFloor);
  const M usable =
      hn::And(hn::Gt(norm_sq, hn::Mul(floor2, hn::Mul(la, lb))), hn::Ne(norm_sq, zero));
  // ProjectTwo of each, and SeparatedAlong.
  const V a_at = Dot(axis, a_start), a_at_off = Dot(axis, a_off);
  const V b_at = Dot(axis, b_start), b_at_off = Dot(axis, b_off);
  const V a_lo = MinOf(a_at, a_at_off), a_hi = MaxOf(a_at, a_at_off);
  const V b_lo = MinOf(b_at, b_at_off), b_hi = MaxOf(b_at, b_at_off);
  const V gap = MaxOf(hn::Sub(a_lo, b_hi), hn::Sub(b_lo, a_hi));
  const M separated = hn::And(
      usable, hn::And(hn::Gt(gap, zero),
                      hn::Gt(hn::Mul(gap, gap), hn::Mul(hn::Set(d, margin * margin), norm_sq))));
  // The gap and lever, where the axis stays usable while the gap lasts.
  const V floor_sq = hn::Mul(hn::Mul(floor2, la), lb);
  const M kept =
      hn::And(separated,
              hn::Gt(norm_sq, hn::Mul(hn::Mul(hn::Set(d, 4.0), floor_sq), hn::Set(d, 1 + 1e-6))));
  const auto extreme = [&](auto of, V Point::*x) {
    return of(of(of(of(of(a.corner[0].*x, a.corner[1].*x), a.corner[2].*x), b.corner[0].*x),
                 b.corner[1].*x),
              b.corner[2].*x);
  };
  const auto min_of = [](V p, V q) { return MinOf(p, q); };
  const auto max_of = [](V p, V q) { return MaxOf(p, q); };
  const Point span{hn::Sub(extreme(max_of, &Point::x), extreme(min_of, &Point::x)),
                   hn::Sub(extreme(max_of, &Point::y), extreme(min_of, &Point::y)),
                   hn::Sub(extreme(max_of, &Point::z), extreme(min_of, &Point::z))};
  const V length = hn::Sqrt(norm_sq);
  gap_m = hn::IfThenElseZero(kept, MaxOf(zero, hn::Sub(hn::Div(gap, length), hn::Set(d, margin))));
  lever_m = hn::IfThenElseZero(
      kept,
      hn::Mul(hn::Div(hn::Mul(two, hn::Sqrt(hn::Mul(la, lb))), length), hn::Sqrt(Dot(span, span))));
  return separated;
}

// The face planes of one batch: the corners' distances from the other's
// plane, and where and how far a plane keeps the other face beyond the
// margin.
struct Planes {
  V db[3], da[3];
  V na_sq, nb_sq;
  M beyond;
  V gap;
};
HWY_INLINE Planes FacePlanes(D d, const Faces& a, const Faces& b, double margin) {
  Planes p;
  for (int k = 0; k < 3; ++k) {
    p.db[k] = Dot(a.normal, Minus(b.corner[k], a.corner[0]));
    p.da[k] = Dot(b.normal, Minus(a.corner[k], b.corner[0]));
  }
  p.na_sq = Dot(a.normal, a.normal);
  p.nb_sq = Dot(b.normal, b.normal);
  const PlaneSide side_a = Side(d, p.db, p.na_sq, margin), side_b = Side(d, p.da, p.nb_sq, margin);
  p.beyond = hn::Or(side_a.beyond, side_b.beyond);
  p.gap = Pick(side_a.beyond, side_a.gap, hn::IfThenElseZero(side_b.beyond, side_b.gap));
  return p;
}

// The pairs pairs[index_of(k)] for k in [0, n), a batch of lanes at a
// time: for each batch its faces and how many lanes hold one of the n (a
// short last batch repeats its last pair), then visit(a, b, first, count).
template <typename IndexOf, typename Visit>
void ForEachBatch(const PlacedFace* faces_a, const PlacedFace* faces_b, const TrianglePair* pairs,
                  size_t n, IndexOf&& index_of, Visit&& visit) {
  const D d;
  const size_t lanes = hn::Lanes(d);
  constexpr size_t kMaxLanes = HWY_MAX_BYTES / sizeof(double);
  HWY_ALIGN int64_t offset_a[kMaxLanes], offset_b[kMaxLanes];
  HWY_ALIGN double soa[12 * kMaxLanes];
  const auto* base_a = reinterpret_cast<const double*>(faces_a);
  const auto* base_b = reinterpret_cast<const double*>(faces_b);
  for (size_t first = 0; first < n; first += lanes) {
    const size_t count = std::min(lanes, n - first);
    for (size_t j = 0; j < lanes; ++j) {
      const TrianglePair& pair = pairs[index_of(first + std::min(j, count - 1))];
      offset_a[RowOfLane(j)] = pair.a * kFaceDoubles;
      offset_b[RowOfLane(j)] = pair.b * kFaceDoubles;
    }
    visit(LoadFaces(d, base_a, offset_a, soa, kMaxLanes),
          LoadFaces(d, base_b, offset_b, soa, kMaxLanes), first, count);
  }
}

using Answer = QuickTriangleTest::Answer;

V AsDouble(D d, Answer answer) { return hn::Set(d, static_cast<double>(answer)); }

// The face planes and the clear crossing of each batch at once.
void PlanesAndCrossing(const PlacedFace* faces_a, const PlacedFace* faces_b,
                       const TrianglePair* pairs, size_t n, double margin, QuickTriangleTest* out) {
  const D d;
  constexpr size_t kMaxLanes = HWY_MAX_BYTES / sizeof(double);
  HWY_ALIGN double answers[kMaxLanes], gaps[kMaxLanes];
  ForEachBatch(
      faces_a, faces_b, pairs, n, [](size_t k) { return k; },
      [&](const Faces& a, const Faces& b, size_t first, size_t count) {
        const Planes p = FacePlanes(d, a, b, margin);
        const M meet = ClearlyCross(d, CrossTheLine(d, a, p.da, p.na_sq, b, p.db, p.nb_sq));
        hn::Store(Pick(p.beyond, AsDouble(d, Answer::kApart),
                       hn::IfThenElseZero(meet, AsDouble(d, Answer::kMeet))),
                  d, answers);
        hn::Store(p.gap, d, gaps);
        for (size_t j = 0; j < count; ++j) {
          out[first + j] = {.answer = static_cast<Answer>(static_cast<int>(answers[j])),
                            .gap_m = gaps[j]};
        }
      });
}

// A stretch at a time, the face planes of every pair, then the crossing
// tests, edge cross too, of those no plane keeps apart, then the nine
// edge crosses of those with no crossing to compare.
void PlanesThenCrossing(const PlacedFace* faces_a, const PlacedFace* faces_b,
                        const TrianglePair* pairs, size_t n, double margin,
                        QuickTriangleTest* out) {
  const D d;
  constexpr size_t kMaxLanes = HWY_MAX_BYTES / sizeof(double);
  HWY_ALIGN double answers[kMaxLanes], gaps[kMaxLanes], edge_pairs[kMaxLanes],
      no_crossing[kMaxLanes];
  constexpr size_t kStretch = 64;
  uint32_t rest[kStretch], unanswered[kStretch];
  for (size_t start = 0; start < n; start += kStretch) {
    size_t rest_size = 0, unanswered_size = 0;
    ForEachBatch(
        faces_a, faces_b, pairs, std::min(kStretch, n - start), [&](size_t k) { return start + k; },
        [&](const Faces& a, const Faces& b, size_t first, size_t count) {
          const Planes p = FacePlanes(d, a, b, margin);
          hn::Store(hn::IfThenElseZero(p.beyond, hn::Set(d, 1.0)), d, answers);
          hn::Store(p.gap, d, gaps);
          for (size_t j = 0; j < count; ++j) {
            const size_t i = start + first + j;
            if (answers[j] != 0) {
              out[i] = {.answer = Answer::kApart, .gap_m = gaps[j]};
            } else {
              rest[rest_size++] = static_cast<uint32_t>(i);
            }
          }
        });
    ForEachBatch(
        faces_a, faces_b, pairs, rest_size, [&](size_t k) { return rest[k]; },
        [&](const Faces& a, const Faces& b, size_t first, size_t count) {
          const Planes p = FacePlanes(d, a, b, margin);
          const Crossings c = CrossTheLine(d, a, p.da, p.na_sq, b, p.db, p.nb_sq);
          V edges;
          const M apart = EdgesApart(d, a, b, c, margin, edges);
          hn::Store(Pick(ClearlyCross(d, c), AsDouble(d, Answer::kMeet),
                         hn::IfThenElseZero(apart, AsDouble(d, Answer::kEdgesApart))),
                    d, answers);
          hn::Store(Pick(apart, edges, hn::Set(d, -1.0)), d, edge_pairs);
          for (size_t j = 0; j < count; ++j) {
            out[rest[first + j]] = {.answer = static_cast<Answer>(static_cast<int>(answers[j])),
                                    .edge_pair = static_cast<int8_t>(edge_pairs[j])};
          }
          if (hn::AllTrue(d, c.valid)) return;  // (the short last batch's lanes repeat)
          hn::Store(hn::IfThenZeroElse(c.valid, hn::Set(d, 1.0)), d, no_crossing);
          for (size_t j = 0; j < count; ++j) {
            if (no_crossing[j] != 0) unanswered[unanswered_size++] = rest[first + j];
          }
        });
    ForEachBatch(
        faces_a, faces_b, pairs, unanswered_size, [&](size_t k) { return unanswered[k]; },
        [&](const Faces& a, const Faces& b, size_t first, size_t count) {
          V edges;
          const M apart = FirstEdgeCrossApart(d, a, b, margin, edges);
          hn::Store(hn::IfThenElseZero(apart, hn::Set(d, 1.0)), d, answers);
          hn::Store(edges, d, edge_pairs);
          for (size_t j = 0; j < count; ++j) {
            if (answers[j] != 0) {
              out[unanswered[first + j]] = {.answer = Answer::kEdgesApart,
                                            .edge_pair = static_cast<int8_t>(edge_pairs[j])};
            }
          }
        });
  }
}

// HintedEdgeCrossBatch's lanes.
void HintedLanes(const PlacedFace* faces_a, const PlacedFace* faces_b, const TrianglePair* pairs,
                 size_t n, double margin, PairHint* hints, uint8_t* separated) {
  const D d;
  constexpr size_t kMaxLanes = HWY_MAX_BYTES / sizeof(double);
  HWY_ALIGN double edge_pairs[kMaxLanes], apart[kMaxLanes], gaps[kMaxLanes], levers[kMaxLanes];
  ForEachBatch(
      faces_a, faces_b, pairs, n, [](size_t k) { return k; },
      [&](const Faces& a, const Faces& b, size_t first, size_t count) {
        for (size_t j = 0; j < hn::Lanes(d); ++j) {
          edge_pairs[j] = hints[first + std::min(j, count - 1)].edge_pair;
        }
        V gap, lever;
        const M sep = HintedEdgeCross(d, a, b, hn::Load(d, edge_pairs), margin, gap, lever);
        hn::Store(hn::IfThenElseZero(sep, hn::Set(d, 1.0)), d, apart);
        hn::Store(gap, d, gaps);
        hn::Store(lever, d, levers);
        for (size_t j = 0; j < count; ++j) {
          separated[first + j] = apart[j] != 0;
          hints[first + j].gap_m = gaps[j];
          hints[first + j].lever_m = levers[j];
        }
      });
}

// FacePlanesApartBatch's lanes.
void PlanesApartLanes(const PlacedFace* faces_a, const PlacedFace* faces_b,
                      const TrianglePair* pairs, size_t n, double margin, uint8_t* apart) {
  const D d;
  constexpr size_t kMaxLanes = HWY_MAX_BYTES / sizeof(double);
  HWY_ALIGN double beyond[kMaxLanes];
  ForEachBatch(
      faces_a, faces_b, pairs, n, [](size_t k) { return k; },
      [&](const Faces& a, const Faces& b, size_t first, size_t count) {
        hn::Store(hn::IfThenElseZero(FacePlanes(d, a, b, margin).beyond, hn::Set(d, 1.0)), d,
                  beyond);
        for (size_t j = 0; j < count; ++j) apart[first + j] = beyond[j] != 0;
      });
}

// Without `edge_cross`, one pass; with it, two, the planes first. (A
// static query's pairs mostly lie beyond a plane, and the crossing tests
// cost several times the planes'; most of a coherent query's cross or
// touch, and one pass costs it less.)
void QuickLanes(const PlacedFace* faces_a, const PlacedFace* faces_b, const TrianglePair* pairs,
                size_t n, double margin, bool edge_cross, QuickTriangleTest* out) {
  if (edge_cross) {
    PlanesThenCrossing(faces_a, faces_b, pairs, n, margin, out);
  } else {
    PlanesAndCrossing(faces_a, faces_b, pairs, n, margin, out);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace hs
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace hs {

HWY_EXPORT(QuickLanes);
HWY_EXPORT(HintedLanes);
HWY_EXPORT(PlanesApartLanes);

void QuickTrianglesTestBatch(const PlacedFace* faces_a, const PlacedFace* faces_b,
                             std::span<const TrianglePair> pairs, double margin, bool edge_cross,
                             std::span<QuickTriangleTest> out) {
  HWY_DYNAMIC_DISPATCH(QuickLanes)
  (faces_a, faces_b, pairs.data(), pairs.size(), margin, edge_cross, out.data());
}

void HintedEdgeCrossBatch(const PlacedFace* faces_a, const PlacedFace* faces_b,
                          std::span<const TrianglePair> pairs, double margin,
                          std::span<PairHint> hints, std::span<uint8_t> separated) {
  HWY_DYNAMIC_DISPATCH(HintedLanes)
  (faces_a, faces_b, pairs.data(), pairs.size(), margin, hints.data(), separated.data());
}

void FacePlanesApartBatch(const PlacedFace* faces_a, const PlacedFace* faces_b,
                          std::span<const TrianglePair> pairs, double margin,
                          std::span<uint8_t> apart) {
  HWY_DYNAMIC_DISPATCH(PlanesApartLanes)
  (faces_a, faces_b, pairs.data(), pairs.size(), margin, apart.data());
}

}  // namespace hs
#endif

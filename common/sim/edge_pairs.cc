#include "common/sim/edge_pairs.h"

#include <algorithm>
#include <cmath>

namespace hs {
namespace {

// How two edges' lines stand (LinesOf).
enum class LinesAre { kNearParallel, kTooFar, kEndsApart, kMayMeet };

// The terms of two edges' lines the tests share: tool edge from t_from
// along u, object edge from o_from along v; n = u x v, its length, and
// the sine of their angle; w = t_from - o_from; the closest points of the
// lines at t_from + a u and o_from + b v (a and b are left unset for
// lines near parallel or too far apart).
struct Lines {
  LinesAre are;
  Vector3d n, w;
  double length, sine, a, b;
};

// EdgePairPlane's ends, past which its closest points are off an edge.
constexpr double kEnds = 1e-9;

// The tests on the lines alone (EdgeLinesMayMeet, EdgePairMayGivePlane).
// Under a move of at most the margin, the lines' distance changes by at
// most twice the margin (checked only with a margin: without one, the
// plane's own gap is tested); the closest points slide along the edges by
// at most margin / s under a shift d alone (a |u| changes by
// d.(c v^ - u^) / s^2, with u^, v^ the unit edges and c their cosine: a
// vector of length s), thrice that where the tool may turn too, and never
// less than twice EdgePairPlane's ends (rounding room for a test without
// a margin). Edges whose angle's sine is at most four turns and a
// millionth are left to their segments' distance: their normal may turn
// any way. The order of the operations is
// edge_pairs_batch.cc's, which gives the same answers.
Lines LinesOf(const Vector3d& t_from, const Vector3d& u, double lu, const Vector3d& o_from,
              const Vector3d& v, double lv, const EdgeMove& move) {
  Lines lines;
  lines.n = u.cross(v);
  lines.length = lines.n.norm();
  lines.sine = lines.length / (lu * lv);
  if (!(lines.sine > 4 * move.turn + 1e-6)) {
    lines.are = LinesAre::kNearParallel;
    return lines;
  }
  lines.w = t_from - o_from;
  if (move.margin_m > 0 && std::abs(lines.n.dot(lines.w)) > move.lines_m * lines.length) {
    lines.are = LinesAre::kTooFar;
    return lines;
  }
  const double uu = u.dot(u), uv = u.dot(v), vv = v.dot(v), uw = u.dot(lines.w),
               vw = v.dot(lines.w);
  const double det = uu * vv - uv * uv;
  lines.a = (uv * vw - vv * uw) / det;
  lines.b = (uu * vw - uv * uw) / det;
  const double slide_m = (move.turn > 0 ? 3 : 1) * move.margin_m / lines.sine + 1e-9 * (lu + lv);
  const double past_u = std::max(slide_m / lu, 2 * kEnds),
               past_v = std::max(slide_m / lv, 2 * kEnds);
  lines.are = lines.a < -past_u || lines.a > 1 + past_u || lines.b < -past_v || lines.b > 1 + past_v
                  ? LinesAre::kEndsApart
                  : LinesAre::kMayMeet;
  return lines;
}

}  // namespace

EdgeLengths LengthsOf(const WorldEdge& e) { return {(e.to - e.from).norm(), e.out.norm()}; }

bool EdgePairPlane(const WorldEdge& t, const WorldEdge& o, ConstraintPlane& plane) {
  const Vector3d u = t.to - t.from, v = o.to - o.from;
  Vector3d n = u.cross(v);
  if (!(n.norm() > 1e-9 * u.norm() * v.norm())) return false;
  n.normalize();
  if (n.dot(o.out) < 0) n = -n;
  if (!(n.dot(o.out) > 0 && n.dot(t.out) < 0)) return false;
  // Closest points of the two lines: t.from + a u and o.from + b v.
  const Vector3d w = t.from - o.from;
  const double uu = u.dot(u), uv = u.dot(v), vv = v.dot(v), uw = u.dot(w), vw = v.dot(w);
  const double det = uu * vv - uv * uv;
  const double a = (uv * vw - vv * uw) / det, b = (uu * vw - uv * uw) / det;
  if (a < -kEnds || a > 1 + kEnds || b < -kEnds || b > 1 + kEnds) return false;
  const Vector3d on_tool = t.from + a * u, on_object = o.from + b * v;
  plane.normal_W = n;
  plane.gap_m = n.dot(on_tool - on_object);
  plane.point_W = on_object;
  plane.tool_point_W = on_tool;
  return true;
}

double SegmentDistance(const Vector3d& p0, const Vector3d& p1, const Vector3d& q0,
                       const Vector3d& q1) {
  const Vector3d d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  double s = 0, t = 0;
  if (!(a > 0) && !(e > 0)) return r.norm();
  if (!(a > 0)) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (!(e > 0)) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2), denom = a * e - b * b;
      s = denom > 0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0) {
        t = 0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1) {
        t = 1;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  return (p0 + s * d1 - q0 - t * d2).norm();
}

double SegmentSlack(double lu, double lv) { return 1e-7 * (lu + lv); }

EdgeMove::EdgeMove(double margin_m, double turn, double radius_m, double behind_m)
    : margin_m(margin_m),
      turn(turn),
      radius_m(radius_m),
      behind_m(behind_m),
      segments_m(std::max(radius_m, behind_m) + margin_m),
      lines_m(std::max(radius_m, behind_m) + 2 * margin_m) {}

// First the lines (LinesOf); then the plane's direction: its normal,
// across two edges at an angle whose sine is s, turns by at most turn / s
// (twice that here). A shift turns nothing, but the features placed at the
// new pose round differently, and the normal across edges at a small
// angle turns by that rounding over s: the direction tests keep
// kRounding / s of room. Last, as the dearest test, the edges' distance
// (`apart_m`): such a plane's gap is the distance of two points of the
// edges (to within their ends' slack), which the move changes by at most
// the margin.
bool EdgePairMayGivePlane(const WorldEdge& t, const EdgeLengths& t_lengths, const WorldEdge& o,
                          const EdgeLengths& o_lengths, const EdgeMove& move, double& apart_m) {
  const Vector3d u = t.to - t.from, v = o.to - o.from;
  const double lu = t_lengths.edge_m, lv = o_lengths.edge_m;
  auto near_enough = [&](double distance_m) {
    apart_m = distance_m;
    return apart_m <= move.segments_m + SegmentSlack(lu, lv);
  };
  auto segments_near_enough = [&] {
    return near_enough(SegmentDistance(t.from, t.to, o.from, o.to));
  };
  if (move.margin_m == 0) {
    ConstraintPlane plane;
    return EdgePairPlane(t, o, plane) && plane.gap_m >= -move.behind_m &&
           plane.gap_m <= move.radius_m && segments_near_enough();
  }
  const Lines lines = LinesOf(t.from, u, lu, o.from, v, lv, move);
  if (lines.are == LinesAre::kNearParallel) return segments_near_enough();
  if (lines.are != LinesAre::kMayMeet) return false;
  constexpr double kRounding = 1e-9;
  const double turned = (2 * move.turn + kRounding) / lines.sine;
  const double out_o = o_lengths.out_norm, out_t = t_lengths.out_norm;
  if (!(out_o > 0 && out_t > 0)) return false;
  const double along_o = lines.n.dot(o.out) / (lines.length * out_o),
               along_t = lines.n.dot(t.out) / (lines.length * out_t);
  const bool either = (along_o >= -turned && along_t <= turned + move.turn) ||
                      (-along_o >= -turned && -along_t <= turned + move.turn);
  if (!either) return false;
  if (lines.a >= 0 && lines.a <= 1 && lines.b >= 0 && lines.b <= 1) {
    // The lines' closest points lie on both edges: the edges' distance is
    // the lines'.
    return near_enough(std::abs(lines.n.dot(lines.w)) / lines.length);
  }
  return segments_near_enough();
}

bool EdgeLinesMayMeet(const Vector3d& t_from, const Vector3d& u, double lu, const Vector3d& o_from,
                      const Vector3d& v, double lv, const EdgeMove& move) {
  const LinesAre are = LinesOf(t_from, u, lu, o_from, v, lv, move).are;
  return are == LinesAre::kNearParallel || are == LinesAre::kMayMeet;
}

}  // namespace hs

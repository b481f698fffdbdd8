#pragma once
// A tool edge and an object edge of a local contact model
// (local_model_builder.h): the plane they give when they meet, and the
// tests of whether they may give one after the tool has moved a little.

#include "common/core/types.h"
#include "common/sim/local_model.h"

namespace hs {

/// An edge in the world frame: its ends and the sum of its faces' normals
/// (which side is out).
struct WorldEdge {
  Vector3d from, to, out;
};

/// An edge's length and the norm of its `out`, each taken once per search
/// rather than once per pair the edge is tested in.
struct EdgeLengths {
  double edge_m, out_norm;
};
EdgeLengths LengthsOf(const WorldEdge& e);

/// The plane where tool edge `t` meets object edge `o` when the tool moves
/// along it: normal t x o, out of the object and into neither side's
/// faces; the closest points of the lines must lie on both edges. False
/// for parallel edges (the vertex pairs hold those) and edges that cannot
/// meet that way. Sets the plane's normal, gap and points only.
bool EdgePairPlane(const WorldEdge& t, const WorldEdge& o, ConstraintPlane& plane);

/// The distance between segments [p0, p1] and [q0, q1], up to rounding
/// (Ericson, Real-Time Collision Detection, 5.1.9): at most 1e-8 of their
/// lengths more than the true one, nearly parallel segments included.
double SegmentDistance(const Vector3d& p0, const Vector3d& p1, const Vector3d& q0,
                       const Vector3d& q1);

/// What SegmentDistance may overstate the distance by, and what
/// EdgePairPlane's ends (1e-9 of an edge past either end) may understate
/// a plane's gap by, for edges of lengths `lu` and `lv`.
double SegmentSlack(double lu, double lv);

/// How far a tool edge and an object edge may be from giving a plane and
/// still give one after the tool has moved: by at most `margin_m` (>= 0),
/// turning by at most `turn` (radians, >= 0), the plane's gap within
/// [-behind_m, radius_m].
struct EdgeMove {
  EdgeMove(double margin_m, double turn, double radius_m, double behind_m);
  double margin_m, turn, radius_m, behind_m;
  /// The most the edges' segments may be apart (to within their
  /// SegmentSlack): max(radius_m, behind_m) and the margin.
  double segments_m;
  /// The most the edges' lines may be apart: max(radius_m, behind_m) and
  /// twice the margin.
  double lines_m;
};

/// Whether tool edge `t` and object edge `o` may give a plane
/// (EdgePairPlane, its gap in [-behind_m, radius_m]) once the tool has
/// moved as `move` allows; `apart_m` is set to their segments' distance
/// when the answer rests on it. Without a margin, the test itself.
bool EdgePairMayGivePlane(const WorldEdge& t, const EdgeLengths& t_lengths, const WorldEdge& o,
                          const EdgeLengths& o_lengths, const EdgeMove& move, double& apart_m);

/// The first of EdgePairMayGivePlane's tests, on the edges' lines alone,
/// for tool edge from `t_from` along `u` (length `lu`) and object edge
/// from `o_from` along `v` (length `lv`): whether the lines' distance and
/// where their closest points fall leave room for a plane. False only
/// where EdgePairMayGivePlane is false; true for edges whose angle's sine
/// is at most 4 turns and a millionth. It turns most of a search's
/// pairs away, and a batch of object edges takes it at once
/// (edge_pairs_batch.h).
bool EdgeLinesMayMeet(const Vector3d& t_from, const Vector3d& u, double lu, const Vector3d& o_from,
                      const Vector3d& v, double lv, const EdgeMove& move);

}  // namespace hs

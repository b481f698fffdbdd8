#pragma once
// Builds a tool's local contact model (local_model.h) from the faces of the
// fixed objects near its proxy.

#include <span>

#include "common/contact/contact_query.h"
#include "common/sim/edge_pairs.h"
#include "common/sim/local_model.h"
#include "common/sim/proxy.h"
#include "common/sim/step_frame.h"

namespace hs {

struct LocalModelOptions {
  /// The model's validity radius, metres, > 0.
  double radius_m = 0.01;
  /// The most planes a model holds (the nearest are kept).
  int max_planes = 16;
  double force_clamp_n = 10;
  bool friction = false;
};

/// A triangle in the world frame with its unit normal (out of its object).
struct WorldFace {
  Vector3d a, b, c, n;
};

/// What moves of the proxy from where pairs are gathered they must serve:
/// any within the margin, or only those without a turn. A turn moves the
/// edges' closest points and their planes' normals more than a shift does,
/// so a search for shifts alone keeps fewer edge pairs.
enum class ProxyMoves { kAny, kShiftsOnly };

/// The pairs of features of a tool and the fixed objects near it (a tool
/// vertex and an object face, an object vertex and a tool face, a tool edge
/// and an object edge) that may give a plane of the tool's local model while
/// the tool stays within `margin_m` of where they were gathered (Moved): a
/// model is made from them (ModelFromPairs) at each step's proxy, and only
/// a proxy that moved farther needs the face search again. The objects'
/// features are kept in the world frame, the tool's by id.
struct LocalModelPairs {
  /// Each pair's `floor_m`: at any proxy pose X_WP, the gap of the plane
  /// it gives (if any) is at least floor_m - Moved(X_WP) (and rounding):
  /// a model needs only the pairs whose floor is near its nearest planes
  /// (ModelFromPairs).
  struct VertexFace {
    VertexId tool_vertex;
    WorldFace face;
    int material;  ///< Index into `materials`.
    double floor_m;
  };
  struct FaceVertex {
    FaceId tool_face;
    Vector3d vertex_W;
    int material;
    double floor_m;
  };
  struct EdgeEdge {
    EdgeId tool_edge;
    WorldEdge edge;
    int material;
    double floor_m;
  };
  /// The proxy pose they were gathered at, and the margin.
  Isometry3d X_WP = Isometry3d::Identity();
  double margin_m = -1;  ///< < 0: never gathered.
  /// Every pair that may give a plane with a gap up to this (metres) is
  /// here; infinite when gathered for the whole radius.
  double complete_m = 0;
  /// The arm a turn of the tool moves the features by (Moved).
  double lever_m = 0;
  /// The moves they serve: with kShiftsOnly, Moved is infinite for any
  /// turn from X_WP.
  ProxyMoves moves = ProxyMoves::kAny;
  /// How many fixed objects there were.
  size_t obstacle_count = 0;
  /// Object id and face material of the pairs' planes (their other fields
  /// unused).
  std::vector<ConstraintPlane> materials;
  std::vector<VertexFace> vertex_faces;
  std::vector<FaceVertex> face_vertices;
  std::vector<EdgeEdge> edge_edges;

  /// How far, at most, any feature of a pair has moved relative to the
  /// other with the proxy at X_WP instead of where they were gathered: the
  /// shift of the origin and the turn times the lever (the farthest point
  /// of the tool or of an object feature within the radius of it, from the
  /// tool's origin); infinite for a turned pose when they serve shifts only.
  double Moved(const Isometry3d& X_WP) const;
};

/// How far a point at `lever_m` from the origin moves at most when a pose
/// goes from `from` to `to`: the shift of the origin and the turn's angle
/// times the lever.
double MovedBy(const Isometry3d& from, const Isometry3d& to, double lever_m);

/// The order of a model's planes: nearest first (by gap); ties in a fixed
/// order, so that a model does not depend on the order its pairs were
/// found in.
bool NearerPlane(const ConstraintPlane& x, const ConstraintPlane& y);

/// Sets what `model` says of the proxy it is taken at: its pose, the
/// device position it moved toward, and its touch (the contact point; the
/// proxy's origin when it touches nothing).
void SetModelProxy(const ProxyState& proxy, const Vector3d& p_WD, LocalModel& model);

/// Sets what `model` says besides its planes and surface: the proxy, as
/// SetModelProxy, and the options it is made with.
void SetModelState(const ProxyState& proxy, const Vector3d& p_WD, const LocalModelOptions& options,
                   LocalModel& model);

/// How far behind a plane a tool may lie and still count as resting on it:
/// the proxy stands 1e-6 of the tool's size in front of what it touches,
/// so a pair farther behind is not one the tool rests on.
double PlaneTouchTolerance(const HapticObject& tool);

/// Fills `pairs` for `tool` (its pose field ignored) at proxy pose X_WP
/// among `obstacles` (fixed objects, ids `ids`): every pair BuildLocalModel
/// would take a plane from with the proxy anywhere `Moved` says is within
/// `margin_m` (>= 0) of X_WP. Allocates nothing once the vectors are large
/// enough.
void GatherLocalModelPairs(const PosedObject& tool, const Isometry3d& X_WP,
                           std::span<const PosedObject> obstacles, std::span<const ObjectId> ids,
                           const LocalModelOptions& options, double margin_m,
                           LocalModelPairs& pairs);

/// As above, but only the pairs that may give a plane with a gap up to
/// `reach_m` (metres, in (0, options.radius_m]; the whole radius at or
/// over it): a shorter search where the model's nearest planes are much
/// nearer than the radius. ModelFromPairs says when they no longer do.
/// And the pairs serve the proxy's `moves`.
void GatherLocalModelPairs(const PosedObject& tool, const Isometry3d& X_WP,
                           std::span<const PosedObject> obstacles, std::span<const ObjectId> ids,
                           const LocalModelOptions& options, double margin_m, double reach_m,
                           ProxyMoves moves, LocalModelPairs& pairs);

/// Fills `model` for `tool` at `proxy`, moved toward the device at `p_WD`,
/// from `pairs`: while `pairs.Moved(proxy.X_WP) <= pairs.margin_m`, the
/// model BuildLocalModel makes there (its revision left as it was), and
/// true. False when the pairs were gathered short of the radius and the
/// model's farthest plane may lie beyond them, or for shifts alone and the
/// proxy turned (then `model` is not the search's: gather again).
bool ModelFromPairs(const HapticObject& tool, const ProxyState& proxy, const Vector3d& p_WD,
                    const LocalModelPairs& pairs, const LocalModelOptions& options,
                    LocalModel& model);

/// Fills `model` for `tool` (its pose field ignored) at `proxy`, moved
/// toward the device at `p_WD`, among `obstacles` (fixed objects, ids
/// `ids`; `proxy.obstacle` is an id): the planes of the translations the
/// tool may make. A pair of features (a tool vertex and an object face,
/// an object vertex and a tool face, two edges) gives a plane when its
/// features, moved along the plane's normal, would meet, and they lie in
/// front by at most the radius; planes that coincide are taken once, the
/// nearest `max_planes` kept. Its revision is left as it was. Allocates
/// nothing once `model.planes` and the query buffers are large enough.
void BuildLocalModel(const PosedObject& tool, const ProxyState& proxy, const Vector3d& p_WD,
                     std::span<const PosedObject> obstacles, std::span<const ObjectId> ids,
                     const LocalModelOptions& options, LocalModel& model);

}  // namespace hs

#pragma once
// What contact reconstruction reports for one colliding object pair
// (paper s.4): whether they penetrate or touch, the reversing vector that
// separates them along the direction of motion, and the first contact
// vertices, edges and faces on each object.

#include <array>
#include <limits>
#include <optional>
#include <vector>

#include "common/core/types.h"

namespace hs {

enum class ContactMethod {
  kPaper2d,  ///< The paper's projections onto the xy, yz and xz planes.
  kSweep3d,  ///< Exact 3D sweep intervals by the separating axis theorem.
};

/// Dimension of a contact feature; ordered vertex < edge < face.
enum class FeatureKind { kNone = 0, kVertex = 1, kEdge = 2, kFace = 3 };

/// One HDS feature of one object.
struct Feature {
  FeatureKind kind = FeatureKind::kNone;
  /// HDS VertexId, EdgeId or FaceId, by kind.
  int32_t id = -1;
  bool operator==(const Feature&) const = default;
  auto operator<=>(const Feature&) const = default;
};

/// One point where the objects touch once separated.
struct ContactPoint {
  /// The point, world frame, metres, with M moved by the reversing vector.
  Vector3d p_WC = Vector3d::Zero();
  /// The lowest-dimensional feature of each object that holds the point.
  Feature moving;
  Feature fixed;
};

/// The contact features of one object. Per the paper: contact vertices two
/// of which share an edge make an edge contact, three on one face a face
/// contact; an edge touched inside (edge-edge contact) is an edge contact,
/// and a face touched inside (by the other's vertex) a face contact.
struct SideContact {
  /// The highest kind among the features below.
  FeatureKind kind = FeatureKind::kNone;
  /// HDS ids, sorted, no repeats.
  std::vector<VertexId> vertices;
  std::vector<EdgeId> edges;
  std::vector<FaceId> faces;
};

/// The contact of a moving object M with a fixed object F.
struct ContactSet {
  ContactMethod method = ContactMethod::kSweep3d;
  /// M penetrates or touches F.
  bool colliding = false;
  /// depth_m is above the tolerance: M is inside F, not just touching.
  bool penetrating = false;
  /// t*: how far M must move back along -direction_W to stop penetrating
  /// (touching allowed), metres, >= 0. The paper's d_max.
  double depth_m = 0;
  /// Unit direction of M's motion relative to F, world frame: the query's
  /// direction, or the fallback one when that was zero (see `fallback`).
  Vector3d direction_W = Vector3d::Zero();
  /// -depth_m * direction_W, world frame, metres: add it to M's position.
  Vector3d reversing_vector_W = Vector3d::Zero();
  /// Unit contact normal, world frame, pointing from F toward M.
  Vector3d normal_W = Vector3d::Zero();
  SideContact moving;
  SideContact fixed;
  std::vector<ContactPoint> points;
  /// The distance under which objects count as touching, metres: the
  /// query's relative tolerance times the pair's size (the sum of the two
  /// objects' bounding-box diagonals).
  double tolerance_m = 0;
  /// The paper's singular case (fig. 6) decided the depth: a vertex of F
  /// inside M with no vertex of M inside F (paper method only).
  bool singular_case = false;
  /// The direction was zero, so an estimated one was used.
  bool fallback = false;
  /// Continuous queries: the fraction of the last step, in [0, 1], at which
  /// M first touched F. When M touched F during the step but no longer does
  /// (it passed through), depth and reversing vector lead back to that
  /// first touch. Unset when not continuous or no touch during the step.
  std::optional<double> time_of_impact;
  /// Paper method: the reversing distance found in each projection plane
  /// (xy, yz, xz), metres; +inf where the plane was unusable or found none.
  /// Exact for the plane that gave depth_m. A plane that cannot change the
  /// answer (its distance plus the tolerance is at least depth_m) stops
  /// once that shows, and holds the distance it had reached: a lower bound
  /// of its own, at least depth_m less the tolerance.
  std::array<double, 3> plane_depths_m = {std::numeric_limits<double>::infinity(),
                                          std::numeric_limits<double>::infinity(),
                                          std::numeric_limits<double>::infinity()};
};

/// Makes `set` a default ContactSet again, keeping its vectors' storage.
inline void ClearContactSet(ContactSet& set) {
  SideContact moving = std::move(set.moving), fixed = std::move(set.fixed);
  std::vector<ContactPoint> points = std::move(set.points);
  set = ContactSet{};
  for (SideContact* side : {&moving, &fixed}) {
    side->kind = FeatureKind::kNone;
    side->vertices.clear();
    side->edges.clear();
    side->faces.clear();
  }
  points.clear();
  set.moving = std::move(moving);
  set.fixed = std::move(fixed);
  set.points = std::move(points);
}

}  // namespace hs

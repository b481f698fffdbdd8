#pragma once
// The local contact model of a tool (an intermediate representation, Adachi
// et al. 1995; Mark et al. 1996): what a remote device needs to render the
// contact by itself, at its own rate, until the next frame brings a newer
// one. The planes near the proxy that the tool must stay in front of, with
// their materials, and the proxy they were taken at. Plain data, so that a
// device's loop (client/haptic_loop) can use it without the simulation.

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "common/core/types.h"

namespace hs {

/// A plane the tool must stay in front of: the tangent plane of a face of a
/// fixed object near the proxy.
struct ConstraintPlane {
  /// The object's id in the scene (in a model read from a frame, which
  /// names its objects: 0 for the first object it names, 1 for the next).
  int32_t object = -1;
  /// On the plane: the point nearest the tool at the model's proxy pose,
  /// world frame, metres.
  Vector3d point_W = Vector3d::Zero();
  /// Unit, world frame, out of the object (toward the tool).
  Vector3d normal_W = Vector3d::UnitZ();
  /// How far the tool at the model's proxy pose is in front of the plane,
  /// metres, >= 0.
  double gap_m = 0;
  /// The tool's point nearest the plane at the model's proxy pose, world
  /// frame, metres: the lever of the torque when the tool leans on this
  /// plane and the proxy touched nothing.
  Vector3d tool_point_W = Vector3d::Zero();
  /// The face's material: spring N/m, damper N*s/m, Coulomb coefficients.
  double stiffness_n_per_m = 0;
  double damping_ns_per_m = 0;
  double static_friction = 0;
  double dynamic_friction = 0;
  /// The plane separates the tool from its whole object near it: in front
  /// of it, within the validity radius, the tool meets nothing of that
  /// object, whatever the object's other planes say. A device keeps the tool out of the region
  /// behind every separating plane of an object (a convex region), and
  /// behind each of the object's other planes only while it has none.
  bool separating = false;
};

/// A face's material as a model carries it: spring N/m, damper N*s/m,
/// Coulomb coefficients.
struct ModelMaterial {
  double stiffness_n_per_m = 0;
  double damping_ns_per_m = 0;
  double static_friction = 0;
  double dynamic_friction = 0;
};

/// The most a surface carries: faces, materials, and the tool's hull
/// vertices (a hull of n vertices has at most 2n - 4 triangles). A tool or
/// a neighbourhood past them gets planes alone. A device's loop holds
/// room for the most from the start, so that taking a surface allocates
/// nothing.
inline constexpr int kMaxSurfaceTriangles = 8192;
inline constexpr int kMaxSurfaceMaterials = 256;
inline constexpr int kMaxToolHullVertices = 64;
inline constexpr int kMaxToolHullTriangles = 2 * kMaxToolHullVertices - 4;

/// The faces of the fixed objects near a tool and the tool's convex shape:
/// with them a device's loop moves its proxy against the faces themselves,
/// as the server's proxy does (docs/remote-haptics.md, The surface), so
/// that what it renders does not depend on where and when its model was
/// taken. A tool's models share a surface until its proxy moves on.
struct ModelSurface {
  /// Which of its tool's surfaces this is: 1 for the first, +1 per surface
  /// gathered; 0 for none (the tool is not convex, or too many faces).
  uint64_t revision = 0;
  /// Every face of a fixed object that the tool meets with its origin
  /// within `radius_m` of `center_W`, in any orientation, is here.
  Vector3d center_W = Vector3d::Zero();
  double radius_m = 0;
  /// The tool's convex hull in its own frame (the proxy's), metres: its
  /// vertices and triangles (indices into them). Empty in a model read
  /// from a frame that names a surface its stream already has.
  std::vector<Vector3d> tool_vertices_T;
  std::vector<std::array<int32_t, 3>> tool_triangles;
  /// The faces, world frame, metres: vertices, triangles (indices into
  /// them, counter-clockwise seen from outside), and each triangle's
  /// material (an index into `materials`).
  std::vector<Vector3d> vertices_W;
  std::vector<std::array<int32_t, 3>> triangles;
  std::vector<int32_t> triangle_materials;
  std::vector<ModelMaterial> materials;

  /// The faces and the tool are here (not only the revision).
  bool has_body() const { return !tool_triangles.empty(); }
};

struct LocalModel {
  /// Which of its tool's models this is: 1 for the first built, +1 per
  /// model built; 0 for none. A frame may carry a model again (the server
  /// builds one only when the last one no longer serves): a device's loop
  /// takes each revision once.
  uint64_t revision = 0;
  /// The proxy pose the model was taken at, world frame, metres.
  Isometry3d X_WP = Isometry3d::Identity();
  /// The device's origin the proxy was moved toward, world frame, metres:
  /// a device's loop finds the tick it rendered at that position to learn
  /// how far its own proxy had drifted from the server's.
  Vector3d p_WD = Vector3d::Zero();
  /// How far from the proxy's origin the model holds, metres: every face
  /// of a fixed object within this distance of the tool is behind one of
  /// the planes. A device must not move its proxy farther.
  double validity_radius_m = 0;
  /// The scene's force clamp, newtons.
  double force_clamp_n = 0;
  /// Whether the proxy touched an object at the model's pose, and where
  /// (the tool's touching point, world frame, metres): the lever of the
  /// torque while the tool leans on any plane.
  bool touching = false;
  Vector3d touch_point_W = Vector3d::Zero();
  /// Whether the scene slides its proxies with friction.
  bool friction = false;
  /// Nearest first; several for edges and corners, none in free space.
  std::vector<ConstraintPlane> planes;
  /// The surface the model shares with its tool's other models; none
  /// when null. Shared, not copied: a tool's models and frames hold one.
  std::shared_ptr<const ModelSurface> surface;

  uint64_t surface_revision() const { return surface ? surface->revision : 0; }
};

}  // namespace hs

#include "common/sim/model_surface.h"

#include <algorithm>

#include "common/collision/faces_in_box.h"

namespace hs {

bool IsConvexTool(const HapticObject& tool) {
  // Closed: a device sweeps the tool by its faces' normals and edges,
  // which for an open or flat mesh would miss directions it reaches in.
  for (EdgeId e = 0; e < tool.num_edges(); ++e) {
    if (tool.EdgeFaces(e).size() != 2) return false;
  }
  const double rounding = 1e-9 * tool.bounding_box().diagonal().norm();
  bool solid = false;  // some vertex well behind some face: not flat
  for (const Face& f : tool.faces()) {
    const Vector3d& a = tool.position(f.vertices[0]);
    const Vector3d n = (tool.position(f.vertices[1]) - a).cross(tool.position(f.vertices[2]) - a);
    if (!(n.norm() > 0)) continue;
    const Vector3d unit = n.normalized();
    for (const Vector3d& x : tool.positions()) {
      const double ahead = unit.dot(x - a);
      if (ahead > rounding) return false;
      solid = solid || ahead < -rounding;
    }
  }
  return solid;
}

bool SurfaceKeeper::Serves(const PosedObject& tool, const Vector3d& p_WP, double radius_m,
                           std::span<const PosedObject> obstacles) const {
  if (!gathered_ || tool.model != tool_model_ || tool.model->geometry_version() != tool_version_ ||
      radius_m != radius_m_ || obstacles.size() != obstacles_.size()) {
    return false;
  }
  for (size_t i = 0; i < obstacles.size(); ++i) {
    const ObstacleKey& k = obstacles_[i];
    const PosedObject& o = obstacles[i];
    if (k.model != o.model || k.geometry_version != o.model->geometry_version() ||
        k.material_version != o.object->material_version() ||
        !k.X_WO.matrix().isApprox(o.X_WO.matrix(), 0.0)) {
      return false;
    }
  }
  // A tool that is not convex never gets one; a gather past the caps is
  // tried again once the proxy has moved on.
  return !convex_ || (p_WP - center_W_).norm() <= kSurfaceMoveFraction * radius_m;
}

bool SurfaceKeeper::Gather(const PosedObject& tool, const Vector3d& center_W, double radius_m,
                           std::span<const PosedObject> obstacles, ModelSurface& out) {
  const HapticObject& shape = *tool.object;
  out.center_W = center_W;
  out.radius_m = kSurfaceReachFraction * radius_m;
  out.tool_vertices_T.assign(shape.positions().begin(), shape.positions().end());
  out.tool_triangles.clear();
  for (const Face& f : shape.faces()) out.tool_triangles.push_back(f.vertices);
  out.vertices_W.clear();
  out.triangles.clear();
  out.triangle_materials.clear();
  out.materials.clear();
  // Any orientation: the tool's farthest vertex from its origin, beyond
  // the reach.
  const double half = tool_reach_m_ + out.radius_m;
  const AlignedBox3d box_W(center_W - Vector3d::Constant(half),
                           center_W + Vector3d::Constant(half));
  for (const PosedObject& o : obstacles) {
    faces_.clear();
    FindFacesInBox(*o.model, o.X_WO, box_W, faces_);
    if (faces_.empty()) continue;
    if (out.triangles.size() + faces_.size() > static_cast<size_t>(kMaxSurfaceTriangles)) {
      return false;
    }
    // In id order, so that a surface does not depend on the hierarchy's.
    std::sort(faces_.begin(), faces_.end());
    const HapticObject& object = *o.object;
    const int32_t first_material = static_cast<int32_t>(out.materials.size());
    if (out.materials.size() + object.materials().size() >
        static_cast<size_t>(kMaxSurfaceMaterials)) {
      return false;
    }
    for (const Material& m : object.materials()) {
      out.materials.push_back(
          {m.stiffness_n_per_m, m.damping_ns_per_m, m.static_friction, m.dynamic_friction});
    }
    vertex_index_.assign(object.num_vertices(), -1);
    for (const FaceId f : faces_) {
      const Face& face = object.face(f);
      std::array<int32_t, 3> t;
      for (int k = 0; k < 3; ++k) {
        int32_t& index = vertex_index_[face.vertices[k]];
        if (index < 0) {
          index = static_cast<int32_t>(out.vertices_W.size());
          out.vertices_W.push_back(o.X_WO * object.position(face.vertices[k]));
        }
        t[k] = index;
      }
      out.triangles.push_back(t);
      out.triangle_materials.push_back(first_material + face.material);
    }
  }
  return true;
}

const std::shared_ptr<const ModelSurface>& SurfaceKeeper::Update(
    const PosedObject& tool, const Vector3d& p_WP, double radius_m,
    std::span<const PosedObject> obstacles, bool fresh) {
  changed_ = false;
  if (!fresh && Serves(tool, p_WP, radius_m, obstacles)) return surface_;
  const HapticObject& shape = *tool.object;
  if (tool.model != tool_model_ || tool.model->geometry_version() != tool_version_ || !gathered_) {
    tool_model_ = tool.model;
    tool_version_ = tool.model->geometry_version();
    convex_ = shape.num_vertices() <= kMaxToolHullVertices &&
              shape.num_faces() <= kMaxToolHullTriangles && IsConvexTool(shape);
    tool_reach_m_ = 0;
    for (const Vector3d& x : shape.positions()) tool_reach_m_ = std::max(tool_reach_m_, x.norm());
  }
  gathered_ = true;
  radius_m_ = radius_m;
  center_W_ = p_WP;
  obstacles_.clear();
  for (const PosedObject& o : obstacles) {
    obstacles_.push_back(
        {o.model, o.model->geometry_version(), o.object->material_version(), o.X_WO});
  }
  const bool had = surface_ != nullptr;
  if (!convex_) {
    surface_.reset();
    changed_ = had;
    return surface_;
  }
  // A new object rather than one a frame no longer holds: frames are
  // read and released on other threads.
  auto out = std::make_shared<ModelSurface>();
  if (surface_) {
    out->tool_vertices_T.reserve(surface_->tool_vertices_T.size());
    out->vertices_W.reserve(surface_->vertices_W.size());
    out->triangles.reserve(surface_->triangles.size());
    out->triangle_materials.reserve(surface_->triangle_materials.size());
  }
  surface_.reset();
  if (Gather(tool, p_WP, radius_m, obstacles, *out)) {
    out->revision = ++revisions_;
    surface_ = std::move(out);
  }
  changed_ = had || surface_ != nullptr;
  return surface_;
}

}  // namespace hs

#include "common/api/local_model_convert.h"

#include <algorithm>
#include <cmath>
#include <string_view>
#include <utility>

#include "absl/strings/str_cat.h"
#include "common/api/proto_convert.h"
#include "common/core/status_macros.h"
#include "common/hds/material.h"

namespace hs {
namespace {

namespace pb = haptics::v1;

// A finite number in [low, high], else INVALID_ARGUMENT naming `where`.
absl::StatusOr<double> NumberIn(double value, double low, double high, const std::string& where) {
  if (!(std::isfinite(value) && value >= low && value <= high)) {
    return InvalidField(where, absl::StrCat("must be finite and in [", low, ", ", high, "]"));
  }
  return value;
}

absl::StatusOr<ModelMaterial> MaterialFromProto(const pb::Material& m, const std::string& at) {
  ModelMaterial out;
  HS_ASSIGN_OR_RETURN(out.stiffness_n_per_m, NumberIn(m.stiffness_n_per_m(), 0, kMaxStiffnessNPerM,
                                                      at + ".stiffness_n_per_m"));
  if (!(out.stiffness_n_per_m > 0)) return InvalidField(at + ".stiffness_n_per_m", "must be > 0");
  HS_ASSIGN_OR_RETURN(out.damping_ns_per_m, NumberIn(m.damping_ns_per_m(), 0, kMaxDampingNsPerM,
                                                     at + ".damping_ns_per_m"));
  HS_ASSIGN_OR_RETURN(out.static_friction,
                      NumberIn(m.static_friction(), 0, kMaxFriction, at + ".static_friction"));
  HS_ASSIGN_OR_RETURN(out.dynamic_friction, NumberIn(m.dynamic_friction(), 0, out.static_friction,
                                                     at + ".dynamic_friction"));
  return out;
}

absl::StatusOr<ConstraintPlane> PlaneFromProto(const pb::ConstraintPlane& p,
                                               const std::string& at) {
  ConstraintPlane plane;
  HS_ASSIGN_OR_RETURN(plane.point_W, VectorFromProto(p.point_w_m(), at + ".point_W_m"));
  HS_ASSIGN_OR_RETURN(plane.normal_W, VectorFromProto(p.normal_w(), at + ".normal_W"));
  if (std::abs(plane.normal_W.norm() - 1) > 1e-6) return InvalidField(at + ".normal_W", "not unit");
  HS_ASSIGN_OR_RETURN(plane.gap_m, NumberIn(p.gap_m(), 0, kMaxCoordinate, at + ".gap_m"));
  HS_ASSIGN_OR_RETURN(plane.tool_point_W,
                      VectorFromProto(p.tool_point_w_m(), at + ".tool_point_W_m"));
  HS_ASSIGN_OR_RETURN(const ModelMaterial m, MaterialFromProto(p.material(), at + ".material"));
  plane.stiffness_n_per_m = m.stiffness_n_per_m;
  plane.damping_ns_per_m = m.damping_ns_per_m;
  plane.static_friction = m.static_friction;
  plane.dynamic_friction = m.dynamic_friction;
  plane.separating = p.separating();
  return plane;
}

void MaterialToProto(const ModelMaterial& material, pb::Material* m) {
  m->set_stiffness_n_per_m(material.stiffness_n_per_m);
  m->set_damping_ns_per_m(material.damping_ns_per_m);
  m->set_static_friction(material.static_friction);
  m->set_dynamic_friction(material.dynamic_friction);
}

// Points from x, y, z triples, each finite and within kMaxCoordinate; at
// most `max` of them.
absl::Status PointsFromProto(const google::protobuf::RepeatedField<double>& xyz, int max,
                             const std::string& at, std::vector<Vector3d>& out) {
  if (xyz.size() % 3 != 0) return InvalidField(at, "must hold x, y, z triples");
  if (xyz.size() / 3 > max) return InvalidField(at, absl::StrCat("more than ", max, " points"));
  out.resize(xyz.size() / 3);
  for (int i = 0; i < xyz.size(); ++i) {
    HS_ASSIGN_OR_RETURN(out[i / 3][i % 3], NumberIn(xyz[i], -kMaxCoordinate, kMaxCoordinate, at));
  }
  return absl::OkStatus();
}

// Triangles from index triples, each index below `vertices`, no vertex
// twice in a triangle; at most `max` of them.
absl::Status TrianglesFromProto(const google::protobuf::RepeatedField<uint32_t>& indices,
                                size_t vertices, int max, const std::string& at,
                                std::vector<std::array<int32_t, 3>>& out) {
  if (indices.size() % 3 != 0) return InvalidField(at, "must hold index triples");
  if (indices.size() / 3 > max)
    return InvalidField(at, absl::StrCat("more than ", max, " triangles"));
  out.resize(indices.size() / 3);
  for (int i = 0; i < indices.size(); ++i) {
    if (indices[i] >= vertices) return InvalidField(at, "names a vertex it does not have");
    out[i / 3][i % 3] = static_cast<int32_t>(indices[i]);
  }
  for (const std::array<int32_t, 3>& t : out) {
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) {
      return InvalidField(at, "a triangle repeats a vertex");
    }
  }
  return absl::OkStatus();
}

absl::StatusOr<ModelSurface> SurfaceFromProto(const pb::ModelSurface& s) {
  ModelSurface out;
  out.revision = s.revision();
  const std::string at = "local_model.surface";
  HS_ASSIGN_OR_RETURN(out.center_W, VectorFromProto(s.center_w_m(), at + ".center_W_m"));
  HS_ASSIGN_OR_RETURN(out.radius_m, NumberIn(s.radius_m(), 0, kMaxCoordinate, at + ".radius_m"));
  if (!(out.radius_m > 0)) return InvalidField(at + ".radius_m", "must be > 0");
  if (s.tool_triangles().empty() && s.triangles().empty() && s.tool_vertices_t_m().empty() &&
      s.vertices_w_m().empty() && s.face_materials().empty() && s.materials().empty()) {
    return out;  // the stream has its faces already
  }
  HS_RETURN_IF_ERROR(PointsFromProto(s.tool_vertices_t_m(), kMaxToolHullVertices,
                                     at + ".tool_vertices_T_m", out.tool_vertices_T));
  HS_RETURN_IF_ERROR(TrianglesFromProto(s.tool_triangles(), out.tool_vertices_T.size(),
                                        kMaxToolHullTriangles, at + ".tool_triangles",
                                        out.tool_triangles));
  if (out.tool_triangles.empty()) return InvalidField(at + ".tool_triangles", "must not be empty");
  HS_RETURN_IF_ERROR(PointsFromProto(s.vertices_w_m(), 3 * kMaxSurfaceTriangles,
                                     at + ".vertices_W_m", out.vertices_W));
  HS_RETURN_IF_ERROR(TrianglesFromProto(s.triangles(), out.vertices_W.size(), kMaxSurfaceTriangles,
                                        at + ".triangles", out.triangles));
  if (s.face_materials_size() != static_cast<int>(out.triangles.size())) {
    return InvalidField(at + ".face_materials", "must name one material a face");
  }
  if (s.materials_size() > kMaxSurfaceMaterials) {
    return InvalidField(at + ".materials", absl::StrCat("more than ", kMaxSurfaceMaterials));
  }
  out.materials.reserve(s.materials_size());
  for (int i = 0; i < s.materials_size(); ++i) {
    HS_ASSIGN_OR_RETURN(ModelMaterial m,
                        MaterialFromProto(s.materials(i), absl::StrCat(at, ".materials[", i, "]")));
    out.materials.push_back(m);
  }
  out.triangle_materials.reserve(out.triangles.size());
  for (const uint32_t m : s.face_materials()) {
    if (m >= out.materials.size()) {
      return InvalidField(at + ".face_materials", "names a material it does not have");
    }
    out.triangle_materials.push_back(static_cast<int32_t>(m));
  }
  return out;
}

void SurfaceToProto(const ModelSurface& surface, bool body, pb::ModelSurface* out) {
  out->set_revision(surface.revision);
  VectorToProto(surface.center_W, out->mutable_center_w_m());
  out->set_radius_m(surface.radius_m);
  if (!body) return;
  for (const Vector3d& v : surface.tool_vertices_T) {
    out->mutable_tool_vertices_t_m()->Add(v.data(), v.data() + 3);
  }
  for (const std::array<int32_t, 3>& t : surface.tool_triangles) {
    for (const int32_t i : t) out->add_tool_triangles(static_cast<uint32_t>(i));
  }
  out->mutable_vertices_w_m()->Reserve(3 * static_cast<int>(surface.vertices_W.size()));
  for (const Vector3d& v : surface.vertices_W) {
    out->mutable_vertices_w_m()->Add(v.data(), v.data() + 3);
  }
  out->mutable_triangles()->Reserve(3 * static_cast<int>(surface.triangles.size()));
  for (const std::array<int32_t, 3>& t : surface.triangles) {
    for (const int32_t i : t) out->add_triangles(static_cast<uint32_t>(i));
  }
  for (const int32_t m : surface.triangle_materials)
    out->add_face_materials(static_cast<uint32_t>(m));
  for (const ModelMaterial& m : surface.materials) MaterialToProto(m, out->add_materials());
}

}  // namespace

void LocalModelToProto(const LocalModel& model, const std::vector<std::string>& names,
                       pb::LocalModel* out, bool surface_faces) {
  PoseToProto(model.X_WP, out->mutable_proxy_pose());
  out->set_validity_radius_m(model.validity_radius_m);
  out->set_force_clamp_n(model.force_clamp_n);
  out->set_friction(model.friction);
  out->set_touching(model.touching);
  VectorToProto(model.touch_point_W, out->mutable_touch_point_w_m());
  VectorToProto(model.p_WD, out->mutable_device_position_w_m());
  out->set_revision(model.revision);
  for (const ConstraintPlane& plane : model.planes) {
    pb::ConstraintPlane* p = out->add_planes();
    p->set_object(names[plane.object]);
    VectorToProto(plane.point_W, p->mutable_point_w_m());
    VectorToProto(plane.normal_W, p->mutable_normal_w());
    p->set_gap_m(plane.gap_m);
    VectorToProto(plane.tool_point_W, p->mutable_tool_point_w_m());
    MaterialToProto({plane.stiffness_n_per_m, plane.damping_ns_per_m, plane.static_friction,
                     plane.dynamic_friction},
                    p->mutable_material());
    p->set_separating(plane.separating);
  }
  if (model.surface_revision() != 0) {
    SurfaceToProto(*model.surface, surface_faces, out->mutable_surface());
  }
}

absl::StatusOr<LocalModel> LocalModelFromProto(const pb::LocalModel& model) {
  LocalModel out;
  HS_ASSIGN_OR_RETURN(out.X_WP, PoseFromProto(model.proxy_pose(), "local_model.proxy_pose"));
  HS_ASSIGN_OR_RETURN(out.validity_radius_m, NumberIn(model.validity_radius_m(), 0, kMaxCoordinate,
                                                      "local_model.validity_radius_m"));
  if (!(out.validity_radius_m > 0))
    return InvalidField("local_model.validity_radius_m", "must be > 0");
  HS_ASSIGN_OR_RETURN(out.force_clamp_n,
                      NumberIn(model.force_clamp_n(), 0, 1e6, "local_model.force_clamp_n"));
  if (!(out.force_clamp_n > 0)) return InvalidField("local_model.force_clamp_n", "must be > 0");
  out.revision = model.revision();
  out.friction = model.friction();
  out.touching = model.touching();
  HS_ASSIGN_OR_RETURN(out.touch_point_W,
                      VectorFromProto(model.touch_point_w_m(), "local_model.touch_point_W_m"));
  HS_ASSIGN_OR_RETURN(
      out.p_WD, VectorFromProto(model.device_position_w_m(), "local_model.device_position_W_m"));
  out.planes.reserve(model.planes_size());
  // The planes' objects, numbered in the order the model first names them:
  // a device tells one object's planes from another's by them.
  std::vector<std::string_view> objects;
  for (int i = 0; i < model.planes_size(); ++i) {
    HS_ASSIGN_OR_RETURN(
        ConstraintPlane plane,
        PlaneFromProto(model.planes(i), absl::StrCat("local_model.planes[", i, "]")));
    const std::string_view name = model.planes(i).object();
    const auto known = std::find(objects.begin(), objects.end(), name);
    plane.object = static_cast<int32_t>(known - objects.begin());
    if (known == objects.end()) objects.push_back(name);
    out.planes.push_back(plane);
  }
  if (model.surface().revision() != 0) {
    HS_ASSIGN_OR_RETURN(ModelSurface surface, SurfaceFromProto(model.surface()));
    out.surface = std::make_shared<const ModelSurface>(std::move(surface));
  }
  return out;
}

}  // namespace hs

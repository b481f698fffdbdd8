#include "common/api/scene_geometry.h"

#include "common/api/proto_convert.h"

namespace hs {
namespace {

namespace pb = haptics::v1;

pb::ObjectKind KindToProto(ObjectKind kind) {
  switch (kind) {
    case ObjectKind::kFixed:
      return pb::OBJECT_KIND_FIXED;
    case ObjectKind::kTool:
      return pb::OBJECT_KIND_TOOL;
    case ObjectKind::kFree:
      return pb::OBJECT_KIND_FREE;
  }
  return pb::OBJECT_KIND_UNSPECIFIED;
}

void ObjectGeometryToProto(const SceneObjects::Object& o, const std::string& name,
                           pb::ObjectGeometry* out) {
  const HapticObject& mesh = o.object;
  out->set_name(name);
  out->set_kind(KindToProto(o.kind));
  PoseToProto(o.X_WO, out->mutable_pose());
  out->mutable_vertices_m()->Reserve(3 * mesh.num_vertices());
  for (const Vector3d& p : mesh.positions()) {
    for (int k = 0; k < 3; ++k) out->add_vertices_m(p[k]);
  }
  out->mutable_triangles()->Reserve(3 * mesh.num_faces());
  out->mutable_face_materials()->Reserve(mesh.num_faces());
  for (const Face& f : mesh.faces()) {
    for (const VertexId v : f.vertices) out->add_triangles(v);
    out->add_face_materials(f.material);
  }
  out->mutable_edges()->Reserve(2 * mesh.num_edges());
  for (const Edge& e : mesh.edges()) {
    for (const VertexId v : e.vertices) out->add_edges(v);
  }
  for (const Material& m : mesh.materials()) {
    pb::Material* material = out->add_materials();
    material->set_stiffness_n_per_m(m.stiffness_n_per_m);
    material->set_damping_ns_per_m(m.damping_ns_per_m);
    material->set_static_friction(m.static_friction);
    material->set_dynamic_friction(m.dynamic_friction);
  }
}

}  // namespace

void SceneGeometryToProto(const Scene& scene, const std::vector<std::string>& names,
                          int64_t revision, pb::SceneGeometry* out) {
  out->Clear();
  out->set_revision(revision);
  for (ObjectId id = 0; id < scene.num_objects(); ++id) {
    ObjectGeometryToProto(scene.object(id), names[id], out->add_objects());
  }
}

}  // namespace hs

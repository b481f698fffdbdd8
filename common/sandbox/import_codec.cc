#include "common/sandbox/import_codec.h"

#include "absl/strings/str_cat.h"

namespace hs {

namespace pb = haptics::internal;

void OptionsToJob(const ImportOptions& options, pb::ImportJob& job) {
  job.set_unit_scale(options.unit_scale);
  job.set_weld_relative_tolerance(options.weld_relative_tolerance);
  const Material& m = options.default_material;
  job.set_default_material_name(m.name);
  job.set_stiffness_n_per_m(m.stiffness_n_per_m);
  job.set_damping_ns_per_m(m.damping_ns_per_m);
  job.set_static_friction(m.static_friction);
  job.set_dynamic_friction(m.dynamic_friction);
}

ImportOptions OptionsFromJob(const pb::ImportJob& job) {
  ImportOptions options;
  options.unit_scale = job.unit_scale();
  options.weld_relative_tolerance = job.weld_relative_tolerance();
  options.default_material = Material{.name = job.default_material_name(),
                                      .stiffness_n_per_m = job.stiffness_n_per_m(),
                                      .damping_ns_per_m = job.damping_ns_per_m(),
                                      .static_friction = job.static_friction(),
                                      .dynamic_friction = job.dynamic_friction()};
  return options;
}

pb::ImportedMesh MeshToProto(const ImportedModel& model) {
  pb::ImportedMesh mesh;
  const HapticObject& o = model.object;
  mesh.set_name(o.name());
  mesh.mutable_positions()->Reserve(3 * o.num_vertices());
  for (const Vector3d& p : o.positions()) {
    for (int i = 0; i < 3; ++i) mesh.add_positions(p[i]);
  }
  for (const Face& f : o.faces()) {
    for (VertexId v : f.vertices) mesh.add_face_vertices(v);
    mesh.add_face_materials(f.material);
    mesh.add_face_polygons(f.source_polygon);
  }
  for (const Material& m : o.materials()) {
    pb::ImportedMaterial* out = mesh.add_materials();
    out->set_name(m.name);
    out->set_stiffness_n_per_m(m.stiffness_n_per_m);
    out->set_damping_ns_per_m(m.damping_ns_per_m);
    out->set_static_friction(m.static_friction);
    out->set_dynamic_friction(m.dynamic_friction);
  }
  mesh.set_reader(model.reader);
  const CleaningReport& r = model.cleaning;
  mesh.set_input_vertices(r.input_vertices);
  mesh.set_input_polygons(r.input_polygons);
  mesh.set_input_triangles(r.input_triangles);
  mesh.set_welded_vertices(r.welded_vertices);
  mesh.set_dropped_unreferenced_vertices(r.dropped_unreferenced_vertices);
  mesh.set_dropped_degenerate_triangles(r.dropped_degenerate_triangles);
  mesh.set_dropped_duplicate_triangles(r.dropped_duplicate_triangles);
  return mesh;
}

absl::StatusOr<ImportedModel> MeshFromProto(const pb::ImportedMesh& mesh) {
  const int faces = mesh.face_materials_size();
  if (mesh.positions_size() % 3 != 0 || mesh.face_vertices_size() != 3 * faces ||
      mesh.face_polygons_size() != faces) {
    return absl::InvalidArgumentError("the import worker sent a malformed mesh");
  }
  MeshInput input;
  input.positions.reserve(mesh.positions_size() / 3);
  for (int i = 0; i < mesh.positions_size(); i += 3) {
    input.positions.emplace_back(mesh.positions(i), mesh.positions(i + 1), mesh.positions(i + 2));
  }
  input.faces.reserve(faces);
  for (int f = 0; f < faces; ++f) {
    input.faces.push_back(FaceInput{
        .vertices = {mesh.face_vertices(3 * f), mesh.face_vertices(3 * f + 1),
                     mesh.face_vertices(3 * f + 2)},
        .material = mesh.face_materials(f),
        .source_polygon = mesh.face_polygons(f)});
  }
  for (const pb::ImportedMaterial& m : mesh.materials()) {
    input.materials.push_back(Material{.name = m.name(),
                                       .stiffness_n_per_m = m.stiffness_n_per_m(),
                                       .damping_ns_per_m = m.damping_ns_per_m(),
                                       .static_friction = m.static_friction(),
                                       .dynamic_friction = m.dynamic_friction()});
  }
  absl::StatusOr<HapticObject> object = HapticObject::Create(mesh.name(), std::move(input));
  if (!object.ok()) {
    return absl::InvalidArgumentError(
        absl::StrCat("the import worker sent a bad mesh: ", object.status().message()));
  }
  CleaningReport report{
      .input_vertices = mesh.input_vertices(),
      .input_polygons = mesh.input_polygons(),
      .input_triangles = mesh.input_triangles(),
      .welded_vertices = mesh.welded_vertices(),
      .dropped_unreferenced_vertices = mesh.dropped_unreferenced_vertices(),
      .dropped_degenerate_triangles = mesh.dropped_degenerate_triangles(),
      .dropped_duplicate_triangles = mesh.dropped_duplicate_triangles()};
  return ImportedModel{*std::move(object), report, mesh.reader()};
}

}  // namespace hs

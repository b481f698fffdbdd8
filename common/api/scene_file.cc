#include "common/api/scene_file.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "absl/strings/str_cat.h"
#include "common/api/names.h"
#include "common/api/proto_convert.h"
#include "common/api/proto_file.h"
#include "common/contact/contact_query.h"
#include "common/core/status_macros.h"
#include "common/model/import.h"
#include "common/model/procedural.h"
#include "common/sandbox/sandboxed_import.h"

namespace hs {
namespace {

namespace pb = haptics::v1;

absl::StatusOr<MeshInput> ProceduralMesh(const pb::Procedural& p, const std::string& where) {
  switch (p.shape_case()) {
    case pb::Procedural::kBox: {
      HS_ASSIGN_OR_RETURN(const Vector3d size,
                          VectorFromProto(p.box().size_m(), where + ".box.size_m"));
      if (!(size.array() > 0).all()) return InvalidField(where + ".box.size_m", "must be > 0");
      return MakeBox(size);
    }
    case pb::Procedural::kSphere: {
      const auto& s = p.sphere();
      if (!(s.radius_m() > 0 && s.radius_m() <= kMaxCoordinate)) {
        return InvalidField(where + ".sphere.radius_m", "must be in (0, 1e6]");
      }
      if (s.subdivisions() < 0 || s.subdivisions() > 6) {
        return InvalidField(where + ".sphere.subdivisions", "must be in [0, 6]");
      }
      return MakeIcosphere(s.radius_m(), s.subdivisions());
    }
    case pb::Procedural::kTorus: {
      const auto& t = p.torus();
      if (!(0 < t.minor_radius_m() && t.minor_radius_m() < t.major_radius_m() &&
            t.major_radius_m() <= kMaxCoordinate)) {
        return InvalidField(where + ".torus", "radii must be 0 < minor < major <= 1e6");
      }
      if (t.major_segments() < 3 || t.minor_segments() < 3 || t.major_segments() > 1000 ||
          t.minor_segments() > 1000) {
        return InvalidField(where + ".torus", "segments must be in [3, 1000]");
      }
      return MakeTorus(t.major_radius_m(), t.minor_radius_m(), t.major_segments(),
                       t.minor_segments());
    }
    case pb::Procedural::SHAPE_NOT_SET:
      break;
  }
  return InvalidField(where, "no shape");
}

// Model files a scene file names are the operator's, read in this process
// (an OBJ finds its mtllib beside it); uploaded ones come from clients and
// are read in the import worker (common/sandbox).
enum class Trust { kLocalFile, kUpload };

absl::StatusOr<HapticObject> ImportFile(const std::string& path, double unit_scale,
                                        const std::string& where, Trust trust) {
  ImportOptions options;
  options.unit_scale = unit_scale;
  absl::StatusOr<ImportedModel> model =
      trust == Trust::kLocalFile ? ImportModel(path, options) : SandboxedImport(path, options);
  if (!model.ok()) return InvalidField(where + ".model", std::string(model.status().message()));
  return std::move(model->object);
}

absl::StatusOr<HapticObject> LoadModel(const pb::SceneObject& o, const std::string& where,
                                       const BuildPaths& paths) {
  const pb::ModelSource& source = o.model();
  const double unit_scale = source.unit_scale() == 0 ? 1.0 : source.unit_scale();
  if (!(unit_scale >= 1e-9 && unit_scale <= kMaxCoordinate)) {
    return InvalidField(where + ".model.unit_scale", "must be in [1e-9, 1e6]");
  }
  switch (source.source_case()) {
    case pb::ModelSource::kPath: {
      std::filesystem::path path(source.path());
      if (path.is_relative()) path = std::filesystem::path(paths.base_dir) / path;
      return ImportFile(path.string(), unit_scale, where, Trust::kLocalFile);
    }
    case pb::ModelSource::kUploadedModelId: {
      const std::string& id = source.uploaded_model_id();
      const std::string at = where + ".model.uploaded_model_id";
      if (paths.uploaded_dir.empty()) return InvalidField(at, "uploaded models need a server");
      if (id.empty() || id.find('/') != std::string::npos || id.starts_with(".")) {
        return InvalidField(at, "not a model id");
      }
      const std::filesystem::path path = std::filesystem::path(paths.uploaded_dir) / id;
      if (!std::filesystem::exists(path)) {
        return absl::NotFoundError(absl::StrCat(at, ": no uploaded model '", id, "'"));
      }
      return ImportFile(path.string(), unit_scale, where, Trust::kUpload);
    }
    case pb::ModelSource::kProcedural: {
      HS_ASSIGN_OR_RETURN(MeshInput mesh, ProceduralMesh(source.procedural(), where + ".model"));
      mesh = TransformMesh(std::move(mesh), Isometry3d(Eigen::Scaling(unit_scale)));
      absl::StatusOr<HapticObject> object = HapticObject::Create(o.name(), std::move(mesh));
      if (!object.ok())
        return InvalidField(where + ".model", std::string(object.status().message()));
      return object;
    }
    case pb::ModelSource::SOURCE_NOT_SET:
      break;
  }
  return InvalidField(where + ".model", "no path or procedural shape");
}

absl::Status ApplyMaterials(const pb::SceneObject& o, const std::string& where,
                            HapticObject& object) {
  for (int i = 0; i < o.materials_size(); ++i) {
    const pb::MaterialOverride& m = o.materials(i);
    const std::string at = absl::StrCat(where, ".materials[", i, "]");
    bool found = false;
    for (MaterialId id = 0; id < static_cast<MaterialId>(object.materials().size()); ++id) {
      if (!m.face_group().empty() && object.materials()[id].name != m.face_group()) continue;
      found = true;
      Material material = object.materials()[id];
      material.stiffness_n_per_m = m.material().stiffness_n_per_m() == 0
                                       ? Material{}.stiffness_n_per_m
                                       : m.material().stiffness_n_per_m();
      material.damping_ns_per_m = m.material().damping_ns_per_m();
      material.static_friction = m.material().static_friction();
      material.dynamic_friction = m.material().dynamic_friction();
      if (absl::Status s = object.SetMaterial(id, material); !s.ok()) {
        return InvalidField(at, std::string(s.message()));
      }
    }
    if (!found) return InvalidField(at, absl::StrCat("no face group '", m.face_group(), "'"));
  }
  return absl::OkStatus();
}

absl::StatusOr<ObjectKind> ToKind(const pb::SceneObject& o, const std::string& where) {
  switch (o.kind()) {
    case pb::OBJECT_KIND_FIXED:
      return ObjectKind::kFixed;
    case pb::OBJECT_KIND_TOOL:
      return ObjectKind::kTool;
    case pb::OBJECT_KIND_FREE:
      return ObjectKind::kFree;
    default:
      return InvalidField(where + ".kind",
                          "must be OBJECT_KIND_FIXED, OBJECT_KIND_TOOL or OBJECT_KIND_FREE");
  }
}

absl::StatusOr<BodyOptions> ToBodyOptions(const pb::SceneObject& o, const std::string& where) {
  BodyOptions body;
  if (!o.has_free_body()) return body;
  const std::string at = where + ".free_body";
  if (o.kind() != pb::OBJECT_KIND_FREE) return InvalidField(at, "only for OBJECT_KIND_FREE");
  const pb::FreeBody& b = o.free_body();
  if (!(std::isfinite(b.mass_kg()) && b.mass_kg() >= 0)) {
    return InvalidField(at + ".mass_kg", "must be finite and >= 0");
  }
  if (!(std::isfinite(b.density_kg_per_m3()) && b.density_kg_per_m3() >= 0)) {
    return InvalidField(at + ".density_kg_per_m3", "must be finite and >= 0");
  }
  body.mass_kg = b.mass_kg();
  if (b.density_kg_per_m3() != 0) body.density_kg_per_m3 = b.density_kg_per_m3();
  HS_ASSIGN_OR_RETURN(body.v_W, VectorFromProto(b.velocity_m_per_s(), at + ".velocity_m_per_s"));
  HS_ASSIGN_OR_RETURN(body.w_W, VectorFromProto(b.angular_velocity_rad_per_s(),
                                                at + ".angular_velocity_rad_per_s"));
  return body;
}

absl::Status ApplyVertexMoves(const pb::SceneObject& o, const std::string& where,
                              HapticObject& object) {
  for (int i = 0; i < o.vertex_moves_size(); ++i) {
    const pb::VertexMove& move = o.vertex_moves(i);
    const std::string at = absl::StrCat(where, ".vertex_moves[", i, "]");
    HS_ASSIGN_OR_RETURN(const Vector3d p, VectorFromProto(move.position_m(), at + ".position_m"));
    const VertexId id = move.vertex_id();
    if (absl::Status s = object.MoveVertices({&id, 1}, {&p, 1}); !s.ok()) {
      return InvalidField(at, std::string(s.message()));
    }
  }
  return absl::OkStatus();
}

absl::StatusOr<SceneOptions> ToOptions(const pb::SceneSpec& spec) {
  SceneOptions options;
  if (spec.step_s() != 0) options.step_s = spec.step_s();
  if (spec.relative_tolerance() != 0) options.relative_tolerance = spec.relative_tolerance();
  if (spec.force_clamp_n() != 0) options.force_clamp_n = spec.force_clamp_n();
  if (spec.local_model_radius_m() != 0) options.local_model_radius_m = spec.local_model_radius_m();
  options.local_model_radius_cap_m =
      spec.local_model_radius_cap_m() != 0
          ? spec.local_model_radius_cap_m()
          : std::max(options.local_model_radius_cap_m, options.local_model_radius_m);
  HS_ASSIGN_OR_RETURN(options.enabled,
                      EffectsFromProto(spec.effects(), EffectSet::All(), "effects"));
  if (spec.has_gravity_m_per_s2()) {
    HS_ASSIGN_OR_RETURN(options.gravity_W,
                        VectorFromProto(spec.gravity_m_per_s2(), "gravity_m_per_s2"));
  }
  switch (spec.contact_method()) {
    case pb::CONTACT_METHOD_PAPER_2D:
      options.method = ContactMethod::kPaper2d;
      break;
    case pb::CONTACT_METHOD_UNSPECIFIED:
    case pb::CONTACT_METHOD_SWEEP_3D:
      options.method = ContactMethod::kSweep3d;
      break;
    default:
      return InvalidField("contact_method", "unknown method");
  }
  constexpr BvType kBvs[] = {BvType::kObbRss, BvType::kObbRss, BvType::kObb,
                             BvType::kRss,    BvType::kKios,   BvType::kAabb};
  if (spec.bounding_volume() < 0 || spec.bounding_volume() > pb::BOUNDING_VOLUME_AABB) {
    return InvalidField("bounding_volume", "unknown bounding volume");
  }
  options.bv = kBvs[spec.bounding_volume()];
  return options;
}

}  // namespace

ObjectId FindTool(const LoadedScene& scene, const std::string& name) {
  for (ObjectId id : scene.tools) {
    if (scene.names[id] == name) return id;
  }
  return -1;
}

absl::StatusOr<pb::SceneSpec> ReadSceneFile(const std::string& path) {
  pb::SceneSpec spec;
  HS_RETURN_IF_ERROR(ReadProtoFile(path, spec));
  return spec;
}

absl::StatusOr<LoadedScene> BuildScene(const pb::SceneSpec& spec, const std::string& base_dir) {
  return BuildScene(spec, BuildPaths{base_dir, ""});
}

absl::StatusOr<LoadedScene> BuildScene(const pb::SceneSpec& spec, const BuildPaths& paths) {
  if (!spec.name().empty()) HS_RETURN_IF_ERROR(ValidateName(spec.name()));
  HS_ASSIGN_OR_RETURN(const SceneOptions options, ToOptions(spec));
  LoadedScene loaded;
  HS_ASSIGN_OR_RETURN(loaded.scene, Scene::Create(options));
  std::set<std::string> names;
  for (int i = 0; i < spec.objects_size(); ++i) {
    const pb::SceneObject& o = spec.objects(i);
    if (absl::Status s = ValidateName(o.name()); !s.ok()) {
      return InvalidField(absl::StrCat("objects[", i, "]"), std::string(s.message()));
    }
    const std::string where = absl::StrCat("objects[", i, "] '", o.name(), "'");
    if (!names.insert(o.name()).second) return InvalidField(where, "name must be unique");
    HS_ASSIGN_OR_RETURN(const ObjectKind kind, ToKind(o, where));
    HS_ASSIGN_OR_RETURN(const BodyOptions body, ToBodyOptions(o, where));
    HS_ASSIGN_OR_RETURN(const Isometry3d X_WO, PoseFromProto(o.pose(), where + ".pose"));
    HS_ASSIGN_OR_RETURN(HapticObject object, LoadModel(o, where, paths));
    HS_RETURN_IF_ERROR(ApplyMaterials(o, where, object));
    HS_RETURN_IF_ERROR(ApplyVertexMoves(o, where, object));
    // A model too small for a contact query is refused with the scene,
    // not step after step.
    if (absl::Status size = CheckObjectSize(object); !size.ok()) {
      return InvalidField(where + ".model", std::string(size.message()));
    }
    loaded.triangles += object.num_faces();
    absl::StatusOr<ObjectId> id = loaded.scene->AddObject(std::move(object), kind, X_WO, body);
    if (!id.ok()) return InvalidField(where, std::string(id.status().message()));
    loaded.names.push_back(o.name());
    if (kind == ObjectKind::kTool) loaded.tools.push_back(*id);
  }
  return loaded;
}

absl::StatusOr<LoadedScene> LoadSceneFile(const std::string& path) {
  HS_ASSIGN_OR_RETURN(const pb::SceneSpec spec, ReadSceneFile(path));
  absl::StatusOr<LoadedScene> loaded =
      BuildScene(spec, std::filesystem::path(path).parent_path().string());
  if (!loaded.ok()) {
    return absl::Status(loaded.status().code(),
                        absl::StrCat(path, ": ", loaded.status().message()));
  }
  return loaded;
}

}  // namespace hs

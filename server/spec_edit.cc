#include "server/spec_edit.h"

#include <filesystem>

#include "absl/strings/str_cat.h"

namespace hs {
namespace {

namespace pb = haptics::v1;

pb::SceneObject* FindObject(const std::string& name, pb::SceneSpec& spec) {
  for (pb::SceneObject& o : *spec.mutable_objects()) {
    if (o.name() == name) return &o;
  }
  return nullptr;
}

absl::Status NoObject(const std::string& name) {
  return absl::NotFoundError(absl::StrCat("no object '", name, "' in the scene"));
}

}  // namespace

absl::Status AddObjectToSpec(const pb::SceneObject& object, pb::SceneSpec& spec) {
  if (FindObject(object.name(), spec) != nullptr) {
    return absl::AlreadyExistsError(absl::StrCat("object '", object.name(), "' exists"));
  }
  *spec.add_objects() = object;
  return absl::OkStatus();
}

absl::Status UpdateObjectInSpec(const pb::UpdateObjectRequest& request, pb::SceneSpec& spec) {
  pb::SceneObject* o = FindObject(request.object(), spec);
  if (o == nullptr) return NoObject(request.object());
  if (request.has_pose()) *o->mutable_pose() = request.pose();
  if (request.set_materials()) *o->mutable_materials() = request.materials();
  for (const pb::VertexMove& move : request.vertex_moves()) *o->add_vertex_moves() = move;
  return absl::OkStatus();
}

absl::Status RemoveObjectFromSpec(const std::string& name, pb::SceneSpec& spec) {
  auto* objects = spec.mutable_objects();
  for (int i = 0; i < objects->size(); ++i) {
    if (objects->Get(i).name() != name) continue;
    objects->DeleteSubrange(i, 1);
    return absl::OkStatus();
  }
  return NoObject(name);
}

void SetEffectsInSpec(const pb::SetEffectsRequest& request, pb::SceneSpec& spec) {
  *spec.mutable_effects() = request.effects();
}

void AbsoluteModelPaths(const std::string& base_dir, pb::SceneSpec& spec) {
  for (pb::SceneObject& o : *spec.mutable_objects()) {
    if (!o.model().has_path()) continue;
    const std::filesystem::path path(o.model().path());
    if (path.is_relative()) {
      o.mutable_model()->set_path(
          std::filesystem::absolute(std::filesystem::path(base_dir) / path).string());
    }
  }
}

absl::Status RejectModelPaths(const pb::SceneSpec& spec) {
  for (const pb::SceneObject& o : spec.objects()) {
    if (o.model().has_path()) {
      return absl::PermissionDeniedError(
          absl::StrCat("object '", o.name(),
                       "': model files on the server are not open to clients; upload "
                       "the model (UploadModel) or use a procedural shape"));
    }
  }
  return absl::OkStatus();
}

}  // namespace hs

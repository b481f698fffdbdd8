#pragma once
// Scene files and SceneSpec messages (proto/haptics/v1/scene.proto) into a
// simulation Scene: the proto -> domain side of the edge. Used by the
// server and by hapticctl's offline `simulate`.

#include <memory>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "common/sim/scene.h"
#include "haptics/v1/scene.pb.h"

namespace hs {

struct LoadedScene {
  std::unique_ptr<Scene> scene;
  /// Object names by ObjectId.
  std::vector<std::string> names;
  /// The tools' ids, in file order.
  std::vector<ObjectId> tools;
  /// Triangles over all objects.
  int64_t triangles = 0;
};

/// Where BuildScene finds model files.
struct BuildPaths {
  /// Relative ModelSource paths are taken from here.
  std::string base_dir;
  /// Uploaded models (ModelSource.uploaded_model_id) are files here named by
  /// their id; empty: uploaded models are rejected.
  std::string uploaded_dir;
};

/// The id of tool `name` in `scene`, or -1 when it has no such tool.
ObjectId FindTool(const LoadedScene& scene, const std::string& name);

/// Reads a SceneSpec from `path`: JSON when the name ends in ".json",
/// protobuf text format otherwise. INVALID_ARGUMENT (naming the file) when it
/// does not parse; NOT_FOUND when it does not exist.
absl::StatusOr<haptics::v1::SceneSpec> ReadSceneFile(const std::string& path);

/// Builds the scene `spec` describes; relative model paths are taken from
/// `base_dir`. INVALID_ARGUMENT naming the object and field for anything out
/// of range: non-finite numbers, non-unit quaternions, unknown kinds or
/// effects, duplicate names, unknown face groups, bad models.
absl::StatusOr<LoadedScene> BuildScene(const haptics::v1::SceneSpec& spec,
                                       const std::string& base_dir);
/// As above, with uploaded models from `paths.uploaded_dir` (NOT_FOUND for
/// an id that is not there). Vertex moves are applied after the model is
/// loaded (INVALID_ARGUMENT for an id out of range).
absl::StatusOr<LoadedScene> BuildScene(const haptics::v1::SceneSpec& spec, const BuildPaths& paths);

/// ReadSceneFile then BuildScene with the file's folder.
absl::StatusOr<LoadedScene> LoadSceneFile(const std::string& path);

}  // namespace hs

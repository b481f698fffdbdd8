#pragma once
// Exercise files (haptics.v1.ExerciseSpec, text format or JSON): read,
// checked against their scene, and turned into an Exercise in the world
// frame (common/training/exercise.h).

#include <string>

#include "absl/status/statusor.h"
#include "common/training/exercise.h"
#include "haptics/v1/exercise.pb.h"
#include "haptics/v1/scene.pb.h"

namespace hs {

struct LoadedExercise {
  haptics::v1::ExerciseSpec spec;
  Exercise exercise;
  /// The scene file, resolved against the exercise file's folder, and its
  /// spec.
  std::string scene_file;
  haptics::v1::SceneSpec scene;
};

/// `spec` checked against `scene`: INVALID_ARGUMENT naming the field for
/// an unknown object or tool, a tool that is not one, no targets, a radius,
/// force, hold, limit, time limit or weight that is negative, not finite
/// or (where it must be) zero. Balls become world-frame through their
/// object's pose.
absl::StatusOr<Exercise> ExerciseFromSpec(const haptics::v1::ExerciseSpec& spec,
                                          const haptics::v1::SceneSpec& scene);

/// Reads `path` and its scene file (ReadSceneFile), then ExerciseFromSpec;
/// errors name the file.
absl::StatusOr<LoadedExercise> LoadExerciseFile(const std::string& path);

}  // namespace hs

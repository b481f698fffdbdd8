#include "common/api/exercise_file.h"

#include <cmath>
#include <filesystem>
#include <limits>

#include "absl/strings/str_cat.h"
#include "common/api/proto_convert.h"
#include "common/api/proto_file.h"
#include "common/api/scene_file.h"
#include "common/core/status_macros.h"

namespace hs {
namespace {

namespace pb = haptics::v1;

// A finite number >= 0 (> 0 when `positive`), else the field's error.
absl::Status CheckAmount(double value, const std::string& where, bool positive) {
  if (!std::isfinite(value) || value < 0 || (positive && value == 0)) {
    return InvalidField(where,
                        positive ? "must be a finite number > 0" : "must be finite and >= 0");
  }
  return absl::OkStatus();
}

// The scene's object `name`: its pose and kind; INVALID_ARGUMENT at `where`
// when the scene has none.
absl::StatusOr<const pb::SceneObject*> FindObject(const pb::SceneSpec& scene,
                                                  const std::string& name,
                                                  const std::string& where) {
  for (const pb::SceneObject& o : scene.objects()) {
    if (o.name() == name) return &o;
  }
  return InvalidField(where, absl::StrCat("no object '", name, "' in scene '", scene.name(), "'"));
}

absl::StatusOr<Ball> BallFromSpec(const pb::SphereRegion& sphere, const pb::SceneObject& object,
                                  const std::string& where) {
  HS_RETURN_IF_ERROR(CheckAmount(sphere.radius_m(), where + ".radius_m", true));
  HS_ASSIGN_OR_RETURN(const Vector3d p_OC, VectorFromProto(sphere.center_m(), where + ".center_m"));
  HS_ASSIGN_OR_RETURN(const Isometry3d X_WO, PoseFromProto(object.pose(), where + " object pose"));
  return Ball{X_WO * p_OC, sphere.radius_m()};
}

// An object a target, region or limit may name: in the scene, not a tool.
absl::StatusOr<const pb::SceneObject*> FindTouchable(const pb::SceneSpec& scene,
                                                     const std::string& name,
                                                     const std::string& where) {
  HS_ASSIGN_OR_RETURN(const pb::SceneObject* o, FindObject(scene, name, where));
  if (o->kind() == pb::OBJECT_KIND_TOOL) return InvalidField(where, "'" + name + "' is a tool");
  return o;
}

absl::StatusOr<ScoreWeights> WeightsFromSpec(const pb::ScoreWeights& w) {
  const double values[] = {w.targets(), w.time(),      w.economy(),
                           w.force(),   w.forbidden(), w.smoothness()};
  double sum = 0;
  for (const double v : values) {
    HS_RETURN_IF_ERROR(CheckAmount(v, "weights", false));
    sum += v;
  }
  if (sum == 0) return ScoreWeights{};
  return ScoreWeights{w.targets(), w.time(), w.economy(), w.force(), w.forbidden(), w.smoothness()};
}

}  // namespace

absl::StatusOr<Exercise> ExerciseFromSpec(const pb::ExerciseSpec& spec,
                                          const pb::SceneSpec& scene) {
  Exercise e;
  e.name = spec.name();
  HS_ASSIGN_OR_RETURN(const pb::SceneObject* tool, FindObject(scene, spec.tool(), "tool"));
  if (tool->kind() != pb::OBJECT_KIND_TOOL) {
    return InvalidField("tool", "'" + spec.tool() + "' is not a tool");
  }
  e.tool = spec.tool();
  const pb::Vector3& home = tool->pose().position_m();
  e.tool_home_W = Vector3d(home.x(), home.y(), home.z());
  if (spec.targets().empty()) return InvalidField("targets", "must list at least one target");
  for (int i = 0; i < spec.targets_size(); ++i) {
    const pb::ExerciseTarget& t = spec.targets(i);
    const std::string where = absl::StrCat("targets[", i, "]");
    HS_ASSIGN_OR_RETURN(const pb::SceneObject* o,
                        FindTouchable(scene, t.object(), where + ".object"));
    HS_ASSIGN_OR_RETURN(const Ball region, BallFromSpec(t.sphere(), *o, where + ".sphere"));
    HS_RETURN_IF_ERROR(CheckAmount(t.min_force_n(), where + ".min_force_n", false));
    HS_RETURN_IF_ERROR(CheckAmount(t.max_force_n(), where + ".max_force_n", false));
    HS_RETURN_IF_ERROR(CheckAmount(t.hold_s(), where + ".hold_s", false));
    const double max_force =
        t.max_force_n() == 0 ? std::numeric_limits<double>::infinity() : t.max_force_n();
    if (max_force <= t.min_force_n()) {
      return InvalidField(where + ".max_force_n", "must exceed min_force_n (0: no bound)");
    }
    e.targets.push_back({.name = t.name().empty() ? absl::StrCat("target ", i + 1) : t.name(),
                         .object = t.object(),
                         .region = region,
                         .min_force_n = t.min_force_n(),
                         .max_force_n = max_force,
                         .hold_s = t.hold_s()});
  }
  for (int i = 0; i < spec.forbidden_size(); ++i) {
    const pb::ForbiddenRegion& f = spec.forbidden(i);
    const std::string where = absl::StrCat("forbidden[", i, "]");
    HS_ASSIGN_OR_RETURN(const pb::SceneObject* o,
                        FindTouchable(scene, f.object(), where + ".object"));
    Forbidden forbidden{.object = f.object()};
    if (f.has_sphere()) {
      HS_ASSIGN_OR_RETURN(forbidden.region, BallFromSpec(f.sphere(), *o, where + ".sphere"));
    }
    e.forbidden.push_back(std::move(forbidden));
  }
  for (int i = 0; i < spec.force_limits_size(); ++i) {
    const pb::ForceLimit& l = spec.force_limits(i);
    const std::string where = absl::StrCat("force_limits[", i, "]");
    HS_RETURN_IF_ERROR(FindTouchable(scene, l.object(), where + ".object").status());
    HS_RETURN_IF_ERROR(CheckAmount(l.limit_n(), where + ".limit_n", true));
    e.force_limits.push_back({l.object(), l.limit_n()});
  }
  HS_RETURN_IF_ERROR(CheckAmount(spec.time_limit_s(), "time_limit_s", true));
  e.time_limit_s = spec.time_limit_s();
  HS_ASSIGN_OR_RETURN(e.weights, WeightsFromSpec(spec.weights()));
  return e;
}

absl::StatusOr<LoadedExercise> LoadExerciseFile(const std::string& path) {
  LoadedExercise loaded;
  HS_RETURN_IF_ERROR(ReadProtoFile(path, loaded.spec));
  if (loaded.spec.scene_file().empty()) {
    return absl::InvalidArgumentError(absl::StrCat(path, ": scene_file: must name a scene file"));
  }
  loaded.scene_file =
      (std::filesystem::path(path).parent_path() / loaded.spec.scene_file()).lexically_normal();
  HS_ASSIGN_OR_RETURN(loaded.scene, ReadSceneFile(loaded.scene_file));
  absl::StatusOr<Exercise> exercise = ExerciseFromSpec(loaded.spec, loaded.scene);
  if (!exercise.ok()) {
    return absl::Status(exercise.status().code(),
                        absl::StrCat(path, ": ", exercise.status().message()));
  }
  loaded.exercise = *std::move(exercise);
  return loaded;
}

}  // namespace hs

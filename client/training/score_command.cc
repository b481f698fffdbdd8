#include "client/training/score_command.h"

#include <iostream>

#include "client/device_path.h"
#include "client/exit_codes.h"
#include "client/server_call.h"
#include "client/training/score_json.h"
#include "common/api/exercise_file.h"
#include "common/api/scene_file.h"
#include "common/training/step_scoring.h"

namespace hs::cli {
namespace {

// After the path's last pose the device stays there this long, so that a
// hold begun at the end can finish, seconds.
constexpr double kSettleS = 0.5;

void PrintSummary(const ScoreSummary& s, std::ostream& out) {
  out << "score " << s.score << " / 100, " << (s.completed ? "completed" : "not completed")
      << " in " << s.duration_s << " s: targets " << s.targets_reached << " of " << s.targets
      << ", path " << s.path_length_m << " m (economy " << s.economy << "), max force "
      << s.max_force_n << " N, over the limit " << s.force_limit_exceeded_s << " s (excess "
      << s.excess_impulse_ns << " N*s), forbidden contacts " << s.forbidden_contacts
      << ", jerk rms " << s.jerk_rms << " m/s^3\n";
}

}  // namespace

int RunScore(const ScoreArgs& args, std::ostream& out, std::ostream& err) {
  absl::StatusOr<LoadedExercise> exercise = LoadExerciseFile(args.exercise);
  if (!exercise.ok()) return ReportError("score", exercise.status(), err);
  absl::StatusOr<LoadedScene> scene = LoadSceneFile(exercise->scene_file);
  if (!scene.ok()) return ReportError("score", scene.status(), err);
  const ObjectId tool = FindTool(*scene, exercise->exercise.tool);
  const double step_s = scene->scene->options().step_s;
  absl::StatusOr<std::vector<TimedPose>> path = ReadDevicePath(args.path, 1 / step_s);
  if (!path.ok()) return ReportError("score", path.status(), err);
  if (path->empty()) return ReportError("score", args.path + ": no poses", err);
  Scene& s = *scene->scene;
  s.SetNeeded({Effect::kCollision, Effect::kContactSet, Effect::kReversingVector, Effect::kForce,
               Effect::kFriction});
  Scorer scorer(exercise->exercise);
  size_t next = 0;
  const double end_s = path->back().t_s + kSettleS;
  for (int64_t k = 0; !scorer.done() && static_cast<double>(k) * step_s <= end_s; ++k) {
    // The newest pose due by this step (held until the next).
    bool moved = false;
    while (next < path->size() && (*path)[next].t_s <= static_cast<double>(k) * step_s + 1e-12) {
      ++next;
      moved = true;
    }
    if (moved) {
      if (absl::Status set = s.SetDevicePose(tool, (*path)[next - 1].X_WD); !set.ok()) {
        return ReportError("score", set, err);
      }
    }
    scorer.Add(ScoringFrameFromStep(s.Step(), tool, scene->names));
  }
  const ScoreSummary summary = scorer.Summary();
  if (args.json) {
    out << SummaryJson(summary).dump() << "\n";
  } else {
    PrintSummary(summary, out);
  }
  return kExitOk;
}

void AddScoreCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<ScoreArgs>();
  CLI::App* cmd = app.add_subcommand(
      "score", "Score a training exercise offline along a device path (docs/training.md)");
  cmd->add_option("EXERCISE", args->exercise, "Exercise file (haptics.v1.ExerciseSpec)")
      ->required();
  cmd->add_option("--path", args->path, "Device path: CSV (one pose per step) or JSON lines")
      ->required();
  cmd->add_flag("--json", args->json, "One JSON summary object");
  cmd->callback([args, &exit_code] { exit_code = RunScore(*args, std::cout, std::cerr); });
}

}  // namespace hs::cli

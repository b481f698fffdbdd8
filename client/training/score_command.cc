#include "client/training/score_command.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <optional>

#include "absl/strings/str_cat.h"

#include "client/device_path.h"
#include "client/exit_codes.h"
#include "client/server_call.h"
#include "client/training/report.h"
#include "client/training/score_output.h"
#include "common/api/exercise_file.h"
#include "common/api/scene_file.h"
#include "common/core/status_macros.h"
#include "common/recording/replay.h"
#include "common/training/step_scoring.h"

namespace hs::cli {
namespace {

// After the path's last pose the device stays there this long, so that a
// hold begun at the end can finish, seconds.
constexpr double kSettleS = 0.5;

// What a step must compute for the scorer: contacts and their points, and
// the device's force.
const EffectSet kScoringNeeds{Effect::kCollision, Effect::kContactSet, Effect::kReversingVector,
                              Effect::kForce, Effect::kFriction};

// Steps the exercise's scene along the device path `file`.
absl::Status ScorePath(const LoadedExercise& exercise, const std::string& file, Scorer& scorer) {
  HS_ASSIGN_OR_RETURN(LoadedScene scene, LoadSceneFile(exercise.scene_file));
  const ObjectId tool = FindTool(scene, exercise.exercise.tool);
  const double step_s = scene.scene->options().step_s;
  HS_ASSIGN_OR_RETURN(const std::string path_scene, DevicePathScene(file));
  if (!path_scene.empty() && path_scene != exercise.scene.name()) {
    return absl::InvalidArgumentError(absl::StrCat(file, " is a path in scene '", path_scene,
                                                   "', the exercise's scene is '",
                                                   exercise.scene.name(), "'"));
  }
  HS_ASSIGN_OR_RETURN(const std::vector<TimedPose> path, ReadDevicePath(file, 1 / step_s));
  if (path.empty()) return absl::InvalidArgumentError(file + ": no poses");
  Scene& s = *scene.scene;
  s.SetNeeded(kScoringNeeds);
  size_t next = 0;
  int seated = 0;
  const double end_s = path.back().t_s + kSettleS;
  for (int64_t k = 0; !scorer.done() && static_cast<double>(k) * step_s <= end_s; ++k) {
    // The newest pose due by this step (held until the next).
    bool moved = false;
    while (next < path.size() && path[next].t_s <= static_cast<double>(k) * step_s + 1e-12) {
      ++next;
      moved = true;
    }
    // The first pose seats the device on the tool, as a server does for a
    // device that takes it.
    if (moved) HS_RETURN_IF_ERROR(ApplyDevicePose(s, tool, path[next - 1].X_WD, seated++ == 0));
    ScoringFrame scored = ScoringFrameFromStep(s.Step(), tool, scene.names);
    // The path's times are the device's clock of its poses. After the
    // last, the device holds still sending it every step, so that its
    // clock runs on while a hold begun at the end finishes.
    const double step_time_s = static_cast<double>(k) * step_s;
    if (step_time_s > path.back().t_s) {
      scored.pose_time_s = step_time_s;
    } else if (next > 0) {
      scored.pose_time_s = path[next - 1].t_s;
    }
    scorer.Add(scored);
  }
  return absl::OkStatus();
}

// Re-runs the recorded session `file` of the exercise's scene; `gap` says
// why the replay ended before the session did ("" when it did not: a
// recorder that skipped steps leaves a gap no replay crosses).
absl::Status ScoreRecording(const LoadedExercise& exercise, const std::string& file, Scorer& scorer,
                            std::string& gap) {
  HS_ASSIGN_OR_RETURN(const RecordedSession session, ReadSession(file));
  const std::string& recorded = session.records.front().start().spec().name();
  if (recorded != exercise.scene.name()) {
    return absl::InvalidArgumentError(absl::StrCat(file, " records scene '", recorded,
                                                   "', the exercise's scene is '",
                                                   exercise.scene.name(), "'"));
  }
  // The tool's device inputs in order, each with the device's time of its
  // pose: the replay applies each just before its step.
  std::vector<const haptics::v1::DeviceInput*> inputs;
  for (const haptics::v1::Record& record : session.records) {
    if (record.has_input() && record.input().tool() == exercise.exercise.tool) {
      inputs.push_back(&record.input());
    }
  }
  const double step_s = session.records.front().start().step_s();
  size_t next = 0;
  std::optional<double> pose_time_s;
  ReplayOptions options;
  options.extra_needs = kScoringNeeds;
  options.on_step = [&](double time_s, const StepFrame& frame,
                        const std::vector<std::string>& names) {
    const int64_t step = std::llround(time_s / step_s);
    for (; next < inputs.size() && inputs[next]->step() <= step; ++next) {
      pose_time_s = DevicePoseTime(inputs[next]->device_time_ns());
    }
    const auto tool = std::find(names.begin(), names.end(), exercise.exercise.tool);
    const ObjectId id = tool == names.end() ? -1 : static_cast<ObjectId>(tool - names.begin());
    ScoringFrame scored = ScoringFrameFromStep(frame, id, names);
    scored.time_s = time_s;
    scored.pose_time_s = pose_time_s;
    scorer.Add(scored);
  };
  HS_ASSIGN_OR_RETURN(const ReplayReport report, ReplayRecording(file, options));
  gap = report.stopped_early;
  return absl::OkStatus();
}

}  // namespace

int RunScore(const ScoreArgs& args, std::ostream& out, std::ostream& err) {
  if (args.path.empty() == args.recording.empty()) {
    err << "score: give one of --path and --recording\n";
    return kExitUsage;
  }
  absl::StatusOr<LoadedExercise> exercise = LoadExerciseFile(args.exercise);
  if (!exercise.ok()) return ReportError("score", exercise.status(), err);
  Scorer scorer(exercise->exercise);
  std::string gap;
  const absl::Status scored = args.path.empty()
                                  ? ScoreRecording(*exercise, args.recording, scorer, gap)
                                  : ScorePath(*exercise, args.path, scorer);
  if (!scored.ok()) return ReportError("score", scored, err);
  if (!gap.empty())
    err << "hapticctl score: " << args.recording << ": " << gap << "; scored up to there\n";
  const ScoreSummary summary = scorer.Summary();
  if (!args.report_dir.empty()) {
    const absl::Status written =
        WriteReport(args.report_dir, {.exercise = &exercise->exercise,
                                      .scene = exercise->scene.name(),
                                      .summary = summary,
                                      .trace = &scorer.trace(),
                                      .ended = scorer.done()  ? "done"
                                               : !gap.empty() ? "the recording has a gap: " + gap
                                                              : "the path or recording ended",
                                      .compare = args.compare});
    if (!written.ok()) return ReportError("score", written, err);
  }
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
  cmd->add_option("--path", args->path, "Device path: CSV (one pose per step) or JSON lines");
  cmd->add_option("--recording", args->recording,
                  "A recorded session of the exercise's scene (its first file)");
  cmd->add_flag("--json", args->json, "One JSON summary object");
  cmd->add_option("--report", args->report_dir,
                  "Write report.json, report.html and the plots in this folder");
  cmd->add_option("--compare", args->compare, "Earlier report folders, oldest first");
  cmd->callback([args, &exit_code] { exit_code = RunScore(*args, std::cout, std::cerr); });
}

}  // namespace hs::cli

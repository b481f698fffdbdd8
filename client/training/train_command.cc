#include "client/training/train_command.h"

#include <chrono>
#include <csignal>
#include <filesystem>
#include <iostream>
#include <set>
#include <thread>

#include "client/channel.h"
#include "client/exit_codes.h"
#include "client/training/report.h"
#include "client/training/score_output.h"
#include "common/api/exercise_file.h"
#include "common/api/frame_scoring.h"
#include "haptics/v1/session_service.grpc.pb.h"

namespace hs::cli {
namespace {

namespace pb = haptics::v1;
using Clock = std::chrono::steady_clock;

std::atomic<bool> g_interrupted{false};

void OnInterrupt(int) { g_interrupted = true; }

struct Trainee {
  LoadedExercise exercise;
  Scorer scorer;
};

void PrintProgress(const Trainee& t, std::ostream& out) {
  const ScoreProgress p = t.scorer.progress();
  const int n = static_cast<int>(t.exercise.exercise.targets.size());
  out << t.exercise.exercise.tool << ": " << p.elapsed_s << " s, target "
      << std::min(p.current_target + 1, n) << " of " << n << ", force " << p.force_n << " N";
  if (p.limit_n > 0) out << " (limit " << p.limit_n << " N)";
  out << ", errors " << p.errors << (t.scorer.done() ? ", done" : "") << std::endl;
}

}  // namespace

int RunTrain(const TrainArgs& args, std::ostream& out, std::ostream& err,
             const std::atomic<bool>& stop) {
  std::vector<Trainee> trainees;
  std::set<std::string> tools;
  for (const std::string& file : args.exercises) {
    absl::StatusOr<LoadedExercise> exercise = LoadExerciseFile(file);
    if (!exercise.ok()) return ReportError("train", exercise.status(), err);
    if (!trainees.empty() && exercise->scene.name() != trainees.front().exercise.scene.name()) {
      return ReportError("train",
                         file + ": its scene '" + exercise->scene.name() + "' is not '" +
                             trainees.front().exercise.scene.name() + "'",
                         err);
    }
    if (!tools.insert(exercise->exercise.tool).second) {
      return ReportError("train", file + ": tool '" + exercise->exercise.tool + "' is scored twice",
                         err);
    }
    Exercise scored = exercise->exercise;
    trainees.push_back({*std::move(exercise), Scorer(std::move(scored))});
  }
  if (trainees.empty()) return ReportError("train", "no exercise given", err);
  absl::StatusOr<std::shared_ptr<grpc::Channel>> channel = MakeChannel(args.server);
  if (!channel.ok()) return ReportError("train", channel.status(), err);
  auto stub = pb::SessionService::NewStub(*channel);
  grpc::ClientContext context;
  pb::WatchRequest request;
  request.set_scene(trainees.front().exercise.scene.name());
  for (pb::WatchPart part :
       {pb::WATCH_PART_POSES, pb::WATCH_PART_CONTACTS, pb::WATCH_PART_FORCES}) {
    request.add_parts(part);
  }
  auto stream = stub->Watch(&context, request);
  // Ctrl-C (or `stop`) cancels the stream from here; the loop then ends.
  std::atomic<bool> finished{false};
  std::thread canceller([&] {
    while (!finished && !stop && !g_interrupted)
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    if (!finished) context.TryCancel();
  });
  auto all_done = [&] {
    return std::all_of(trainees.begin(), trainees.end(),
                       [](const Trainee& t) { return t.scorer.done(); });
  };
  pb::Frame frame;
  Clock::time_point next_progress = Clock::now() + std::chrono::seconds(1);
  while (!all_done() && stream->Read(&frame)) {
    for (Trainee& t : trainees)
      t.scorer.Add(ScoringFrameFromProto(frame, t.exercise.exercise.tool, FrameStream::kWatch));
    if (!args.json && Clock::now() >= next_progress) {
      next_progress += std::chrono::seconds(1);
      for (const Trainee& t : trainees) PrintProgress(t, out);
    }
  }
  // Done: the stream is still open, end it. Else it ended by itself (or
  // was cancelled), and Finish says how.
  const bool done = all_done();
  finished = true;
  if (done) context.TryCancel();
  const grpc::Status status = stream->Finish();
  canceller.join();
  const bool cancelled = status.error_code() == grpc::StatusCode::CANCELLED;
  const std::string ended =
      done          ? "done"
      : cancelled   ? "interrupted"
      : status.ok() ? "the scene's stream ended"
                    : StatusCodeName(status.error_code()) + ": " + status.error_message();
  for (const Trainee& t : trainees) {
    const ScoreSummary summary = t.scorer.Summary();
    if (!args.report_dir.empty()) {
      const absl::Status written =
          WriteReport((std::filesystem::path(args.report_dir) / t.exercise.exercise.tool).string(),
                      {.exercise = &t.exercise.exercise,
                       .scene = t.exercise.scene.name(),
                       .summary = summary,
                       .trace = &t.scorer.trace(),
                       .ended = t.scorer.done() ? "done" : ended,
                       .compare = args.compare});
      if (!written.ok()) return ReportError("train", written, err);
    }
    if (args.json) {
      nlohmann::ordered_json line = {{"tool", t.exercise.exercise.tool},
                                     {"exercise", t.exercise.exercise.name},
                                     {"ended", t.scorer.done() ? "done" : ended}};
      line.update(SummaryJson(summary));
      out << line.dump() << "\n";
    } else {
      out << t.exercise.exercise.tool << " (" << (t.scorer.done() ? "done" : ended) << "): ";
      PrintSummary(summary, out);
    }
  }
  if (done || cancelled || status.ok()) return kExitOk;
  err << "train: " << ended << "\n";
  return ExitCodeFor(status);
}

void AddTrainCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<TrainArgs>();
  CLI::App* cmd = app.add_subcommand(
      "train", "Score trainees live on a running scene (docs/training.md): one exercise per tool");
  AddConnectionOptions(*cmd, args->server);
  cmd->add_option("EXERCISE", args->exercises, "Exercise files, one per trainee's tool")
      ->required();
  cmd->add_flag("--json", args->json, "The summaries as JSON lines (no progress lines)");
  cmd->add_option("--report", args->report_dir, "Write each trainee's report in DIR/TOOL");
  cmd->add_option("--compare", args->compare, "Earlier report folders, oldest first");
  cmd->callback([args, &exit_code] {
    std::signal(SIGINT, OnInterrupt);
    static const std::atomic<bool> never{false};
    exit_code = RunTrain(*args, std::cout, std::cerr, never);
  });
}

}  // namespace hs::cli

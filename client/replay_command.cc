#include "client/replay_command.h"

#include <memory>

#include <nlohmann/json.hpp>

#include "client/exit_codes.h"
#include "client/json_text.h"
#include "client/recording_command.h"
#include "common/recording/replay.h"

namespace hs::cli {

int RunReplay(const ReplayArgs& args, std::ostream& out, std::ostream& err) {
  absl::StatusOr<ReplayReport> report =
      ReplayRecording(args.file, ReplayOptions{.uploaded_models_dir = args.model_dir});
  if (!report.ok()) {
    err << "hapticctl replay: " << report.status().message() << "\n";
    return kExitFailure;
  }
  nlohmann::ordered_json summary = {
      {"steps_compared", report->steps_compared},
      {"identical", report->identical},
      {"all_identical", report->all_identical()},
  };
  if (report->first_divergent_step != 0) {
    summary["first_divergence"] = {{"step", report->first_divergent_step},
                                   {"field", report->first_divergent_field}};
  }
  if (!report->stopped_early.empty()) summary["stopped_early"] = report->stopped_early;
  summary["files"] = FilesJson(report->files);
  if (args.json) {
    out << summary.dump() << "\n";
  } else {
    PrintJsonAsText(summary, "", out);
  }
  return report->all_identical() ? kExitOk : kExitDiverged;
}

void AddReplayCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<ReplayArgs>();
  CLI::App* cmd = app.add_subcommand(
      "replay", "Re-run a recorded session offline and compare every frame with the recording");
  cmd->add_option("file", args->file, "The session's first file (.hsrec); later parts follow")
      ->required();
  cmd->add_option("--model-dir", args->model_dir,
                  "Where the uploaded models are (default: the folder the recording names)");
  cmd->add_flag("--json", args->json, "Print one JSON object");
  cmd->callback([args, &exit_code] { exit_code = RunReplay(*args, std::cout, std::cerr); });
}

}  // namespace hs::cli

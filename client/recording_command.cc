#include "client/recording_command.h"

#include <memory>

#include <nlohmann/json.hpp>

#include "client/exit_codes.h"
#include "client/json_text.h"
#include "common/recording/recording_summary.h"

namespace hs::cli {

nlohmann::ordered_json FilesJson(const std::vector<SessionFile>& files) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const SessionFile& f : files) {
    nlohmann::ordered_json file = {{"path", f.path}, {"part", f.part}, {"bytes", f.bytes}};
    file["torn"] = !f.torn_reason.empty();
    if (!f.torn_reason.empty()) {
      file["cut_at_byte"] = f.whole_bytes;
      file["torn_bytes"] = f.bytes - f.whole_bytes;
      file["torn_reason"] = f.torn_reason;
    }
    out.push_back(file);
  }
  return out;
}

int RunRecording(const RecordingArgs& args, std::ostream& out, std::ostream& err) {
  absl::StatusOr<RecordingSummary> s = SummarizeRecording(args.file);
  if (!s.ok()) {
    err << "hapticctl recording: " << s.status().message() << "\n";
    return kExitFailure;
  }
  nlohmann::ordered_json tools = nlohmann::ordered_json::array();
  for (const std::string& tool : s->device_tools) tools.push_back(tool);
  const nlohmann::ordered_json summary = {
      {"scene", s->scene},
      {"start_unix_ns", s->start_unix_ns},
      {"frames", s->frames},
      {"first_step", s->first_step},
      {"last_step", s->last_step},
      {"steps", s->steps},
      {"duration_s", s->duration_s},
      {"device_streams", s->device_streams},
      {"device_tools", tools},
      {"viewer_streams", s->viewer_streams},
      {"inputs", s->inputs},
      {"edits", s->edits},
      {"gaps", s->gaps},
      {"gap_steps", s->gap_steps},
      {"ended", s->ended},
      {"files", FilesJson(s->files)},
  };
  if (args.json) {
    out << summary.dump() << "\n";
  } else {
    PrintJsonAsText(summary, "", out);
  }
  return kExitOk;
}

void AddRecordingCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<RecordingArgs>();
  CLI::App* cmd = app.add_subcommand(
      "recording", "Summarize a recorded session: scene, steps, devices, inputs, edits, torn tail");
  cmd->add_option("file", args->file, "The session's file (.hsrec); later parts are read too")
      ->required();
  cmd->add_flag("--json", args->json, "Print one JSON object");
  cmd->callback([args, &exit_code] { exit_code = RunRecording(*args, std::cout, std::cerr); });
}

}  // namespace hs::cli

#pragma once
// `hapticctl recording FILE`: a recorded session in figures, read locally.

#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "CLI/CLI.hpp"
#include "common/recording/session_reader.h"

namespace hs::cli {

struct RecordingArgs {
  std::string file;
  bool json = false;
};

/// Prints the summary of the session `args.file` begins (text, or one JSON
/// object). kExitOk, or kExitFailure with the error on `err` for a file
/// that is missing or not a recording.
int RunRecording(const RecordingArgs& args, std::ostream& out, std::ostream& err);

void AddRecordingCommand(CLI::App& app, int& exit_code);

/// The files of a session as JSON: path, part, bytes, and where a torn
/// tail was cut (`replay` prints them too).
nlohmann::ordered_json FilesJson(const std::vector<SessionFile>& files);

}  // namespace hs::cli

#pragma once
// `hapticctl replay FILE`: re-runs a recorded session offline and compares
// every frame with the recorded one.

#include <ostream>
#include <string>

#include "CLI/CLI.hpp"

namespace hs::cli {

struct ReplayArgs {
  std::string file;
  std::string model_dir;  // "" for the folder the recording names
  bool json = false;
};

/// Prints steps compared, identical, and the first divergence. kExitOk
/// when every frame is identical, kExitDiverged when one differs or steps
/// could not be re-run, kExitFailure (error on `err`) for a file that is
/// missing, not a recording, or a scene that does not build.
int RunReplay(const ReplayArgs& args, std::ostream& out, std::ostream& err);

void AddReplayCommand(CLI::App& app, int& exit_code);

}  // namespace hs::cli

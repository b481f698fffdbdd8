#pragma once
// `hapticctl simulate SCENE --steps N [--tool-path [TOOL=]FILE]...`: runs a
// scene file offline, each tool driven along its own path, and prints every
// step's frame and the per-stage counters.

#include <ostream>
#include <string>
#include <vector>

#include "CLI/CLI.hpp"

namespace hs::cli {

struct SimulateArgs {
  std::string scene_file;
  int steps = 100;
  /// Device paths, "TOOL=FILE" for tool TOOL, or "FILE" for the scene's
  /// first tool; at most one per tool. A file holds one device pose per
  /// line, "x,y,z,rx,ry,rz" (metres, rotation vector in radians); '#'
  /// starts a comment. After its last line the tool stays where it is.
  std::vector<std::string> tool_paths;
  /// What the consumer needs (effect names); empty means everything.
  std::vector<std::string> needs{};
  bool json = false;
};

/// Runs the scene and prints to `out`: one line per step (JSON objects with
/// --json), then the stage statistics. kExitOk, or kExitFailure with the
/// error on `err`.
int RunSimulate(const SimulateArgs& args, std::ostream& out, std::ostream& err);

/// Adds the `simulate` subcommand to `app`; `exit_code` receives its result.
void AddSimulateCommand(CLI::App& app, int& exit_code);

}  // namespace hs::cli

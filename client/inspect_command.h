#pragma once
// `hapticctl inspect FILE`: the HDS summary of a model file, read locally.

#include <ostream>
#include <string>

#include "CLI/CLI.hpp"

namespace hs::cli {

struct InspectArgs {
  std::string file;
  double unit_scale = 1.0;
  double weld_relative_tolerance = 1e-6;
  bool json = false;
};

/// Imports `args.file` and prints its summary (text, or one JSON object) to
/// `out`. Returns kExitOk, or kExitFailure with the error on `err`.
int RunInspect(const InspectArgs& args, std::ostream& out, std::ostream& err);

/// Adds the `inspect` subcommand to `app`; `exit_code` receives its result.
void AddInspectCommand(CLI::App& app, int& exit_code);

}  // namespace hs::cli

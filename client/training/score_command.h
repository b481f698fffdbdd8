#pragma once
// `hapticctl score EXERCISE --path FILE.csv|FILE.jsonl [--json]`: runs the
// exercise's scene offline along a device path for the exercise's tool
// and scores it (common/training/scorer.h), the same scorer a live or
// recorded session goes through.

#include <ostream>
#include <string>

#include "CLI/CLI.hpp"

namespace hs::cli {

struct ScoreArgs {
  std::string exercise;
  /// A device path (device_path.h): CSV, one pose per step, or JSON lines
  /// with times (each pose held until the next).
  std::string path;
  bool json = false;
};

/// Prints the summary to `out` (one JSON object with --json). kExitOk;
/// kExitFailure with the error on `err` for a bad exercise, scene or path.
int RunScore(const ScoreArgs& args, std::ostream& out, std::ostream& err);

/// Adds `score` to `app`; `exit_code` receives its result.
void AddScoreCommand(CLI::App& app, int& exit_code);

}  // namespace hs::cli

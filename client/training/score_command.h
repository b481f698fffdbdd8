#pragma once
// `hapticctl score EXERCISE (--path FILE.csv|FILE.jsonl | --recording FILE)
// [--json]`: scores the exercise's tool (common/training/scorer.h) along a
// device path, run offline in the exercise's scene, or through a recorded
// session, re-run (common/recording/replay.h).

#include <ostream>
#include <string>
#include <vector>

#include "CLI/CLI.hpp"

namespace hs::cli {

struct ScoreArgs {
  std::string exercise{};
  /// A device path (device_path.h): CSV, one pose per step, or JSON lines
  /// with times (each pose held until the next).
  std::string path{};
  /// Or a recorded session of the exercise's scene (its first file).
  std::string recording{};
  bool json = false;
  /// Write a report here (report.h), comparing with these earlier ones.
  std::string report_dir{};
  std::vector<std::string> compare{};
};

/// Prints the summary to `out` (one JSON object with --json). kExitOk;
/// kExitFailure with the error on `err` for a bad exercise, scene or path.
int RunScore(const ScoreArgs& args, std::ostream& out, std::ostream& err);

/// Adds `score` to `app`; `exit_code` receives its result.
void AddScoreCommand(CLI::App& app, int& exit_code);

}  // namespace hs::cli

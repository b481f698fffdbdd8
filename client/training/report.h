#pragma once
// A training run's report (`--report DIR` on `score` and `train`):
// report.json, the plots as PNG from gnuplot (force against time with the
// limits, the path from above and from the side with the targets and
// forbidden balls, and the scores of earlier attempts), and report.html,
// which holds them all (images inline), so it opens with no network and
// no other file.

#include <string>
#include <vector>

#include "absl/status/status.h"
#include "common/training/scorer.h"

namespace hs::cli {

struct ReportInput {
  const Exercise* exercise = nullptr;
  std::string scene;
  ScoreSummary summary;
  const std::vector<TracePoint>* trace = nullptr;
  /// How the run ended: "done", "interrupted", or why it was cut short.
  std::string ended;
  /// Earlier reports' folders (their report.json), oldest first.
  std::vector<std::string> compare;
};

/// Writes DIR/report.json, DIR/force.png, DIR/path.png, DIR/attempts.png
/// (with `compare`) and DIR/report.html, making DIR. INVALID_ARGUMENT for
/// a compared folder without a readable report.json; INTERNAL when
/// gnuplot fails.
absl::Status WriteReport(const std::string& dir, const ReportInput& input);

}  // namespace hs::cli

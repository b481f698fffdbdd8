#pragma once
// What `hapticctl recording FILE` prints: a recorded session in figures.

#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "common/recording/session_reader.h"

namespace hs {

struct RecordingSummary {
  std::string scene;
  int64_t start_unix_ns = 0;
  double step_s = 0;
  std::string frames;  // "full" or "digest"
  /// The steps recorded: first and last (0 when none), how many.
  int64_t first_step = 0;
  int64_t last_step = 0;
  int64_t steps = 0;
  /// Simulated time the recorded steps cover, seconds.
  double duration_s = 0;
  /// Tools driven by a device over the session, and viewer streams.
  std::set<std::string> device_tools;
  int64_t device_streams = 0;
  int64_t viewer_streams = 0;
  int64_t inputs = 0;
  int64_t edits = 0;
  /// Steps the recorder skipped (its queue was full), in how many runs.
  int64_t gaps = 0;
  int64_t gap_steps = 0;
  /// The session's end was recorded (it did not end in a crash).
  bool ended = false;
  std::vector<SessionFile> files;
};

/// Sums up the session `file` begins (and the parts after it).
absl::StatusOr<RecordingSummary> SummarizeRecording(const std::string& file);

}  // namespace hs

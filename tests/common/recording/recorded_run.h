#pragma once
// Test helper: a session recorded without a server. A probe is pressed into
// a table by a device, step by step, the table optionally moved by an edit
// halfway, the scene stepped directly (as a SceneRunner steps it), and
// every record the server's recorder would write is kept, to be written to
// a file, changed, or summed up.

#include <cstdint>
#include <string>
#include <vector>

#include "common/sim/local_model_request.h"
#include "haptics/v1/recording.pb.h"

namespace hs::testing_recording {

/// When the run's session began, and its scene's step.
inline constexpr int64_t kStartUnixNs = 1'800'000'000'000'000'000;
inline constexpr double kStepS = 0.001;

struct RunOptions {
  haptics::v1::FrameRecording frames = haptics::v1::FRAME_RECORDING_FULL;
  int steps = 12;
  /// The step after which an edit moves the table 1 mm down; 0: none.
  int edit_after = 0;
  /// A remote device: the steps also compute the probe's local model, and
  /// every pose asks what `model` says of it (a fresh model at the steps
  /// in `model_stale_at` besides), as the server records it.
  bool remote_device = false;
  LocalModelRequest model;
  std::vector<int> model_stale_at;
};

/// The records of one run: its start, then per step the device input and
/// the frame (an edit before the input where asked), then its end.
std::vector<haptics::v1::Record> RecordRun(const RunOptions& options);

/// Writes `records` to a new file `path` (abort on failure); returns `path`.
std::string WriteRecords(const std::string& path, const std::vector<haptics::v1::Record>& records);

}  // namespace hs::testing_recording

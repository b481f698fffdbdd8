#pragma once
// Replays a recorded session offline: rebuilds its scene from the recorded
// spec, applies every recorded device pose and edit at the step the server
// applied it, steps with the effects each step was asked for, and compares
// each frame with the recorded one.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "common/recording/session_reader.h"
#include "common/sim/step_frame.h"

namespace hs {

struct ReplayOptions {
  /// Where uploaded models are read; "" for the folder the recording names.
  std::string uploaded_models_dir;
  /// Effects every step computes besides those it was asked for (a scorer
  /// needs contacts and forces); frames then differ from the recorded ones
  /// where these add to them.
  EffectSet extra_needs{};
  /// Called after each re-run step with the runner's simulated time
  /// (seconds since the session's scene first stepped), the frame and the
  /// object names by ObjectId.
  std::function<void(double time_s, const StepFrame& frame, const std::vector<std::string>& names)>
      on_step{};
};

struct ReplayReport {
  std::vector<SessionFile> files;
  int64_t steps_compared = 0;
  int64_t identical = 0;
  /// The first step whose frame differs (0: none), and the first field of
  /// it that differs ("frame digest" when only digests were recorded).
  int64_t first_divergent_step = 0;
  std::string first_divergent_field;
  /// Why the replay stopped before the session's last record ("" when it
  /// did not): steps the recorder skipped cannot be re-run.
  std::string stopped_early;
  /// Every recorded step was re-run and every frame is identical.
  bool all_identical() const {
    return steps_compared > 0 && identical == steps_compared && stopped_early.empty();
  }
};

/// INVALID_ARGUMENT for a file that is not a recording, a session whose
/// first file is not given (part > 0), records out of order, or a scene
/// that does not build (naming the model missing).
absl::StatusOr<ReplayReport> ReplayRecording(const std::string& file, const ReplayOptions& options);

}  // namespace hs

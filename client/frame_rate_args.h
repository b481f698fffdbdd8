#pragma once
// --frame-rate-hz: how many frames a second a device asks the server for
// (drive, loadtest), carried in its Interact open message.

#include <CLI/CLI.hpp>

#include "absl/status/status.h"
#include "haptics/v1/session_service.pb.h"

namespace hs::cli {

/// The bounds of --frame-rate-hz, frames per second.
inline constexpr double kMinFrameRateHz = 1;
inline constexpr double kMaxFrameRateHz = 100000;

/// INVALID_ARGUMENT naming --frame-rate-hz unless `hz` is finite and in
/// [kMinFrameRateHz, kMaxFrameRateHz].
absl::Status CheckFrameRate(double hz);

/// Adds --frame-rate-hz to `cmd`, filling `hz` (left as it is when the
/// flag is not given); a value CheckFrameRate refuses is a command-line
/// error.
void AddFrameRateOption(CLI::App& cmd, double& hz);

/// Asks the server for `hz` frames a second in `open`
/// (InteractRequest.Open.frame_rate_hz; 0: nothing asked, one frame a
/// step).
void SetFrameRate(haptics::v1::InteractRequest::Open& open, double hz);

}  // namespace hs::cli

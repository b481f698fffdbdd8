#include "client/frame_rate_args.h"

#include <cmath>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "client/pose_args.h"

namespace hs::cli {

absl::Status CheckFrameRate(double hz) {
  if (std::isfinite(hz) && hz >= kMinFrameRateHz && hz <= kMaxFrameRateHz) {
    return absl::OkStatus();
  }
  return absl::InvalidArgumentError(absl::StrCat("--frame-rate-hz must be a finite number from ",
                                                 kMinFrameRateHz, " to ", kMaxFrameRateHz,
                                                 " frames a second, not ", hz));
}

void AddFrameRateOption(CLI::App& cmd, double& hz) {
  cmd.add_option("--frame-rate-hz", hz,
                 "Frames a second the device asks the server for (1..100000; default: the "
                 "server's rate)")
      ->check(ValueCheck("HZ", [](const std::string& text) {
        double hz = 0;
        if (!absl::SimpleAtod(text, &hz)) {
          return absl::InvalidArgumentError("--frame-rate-hz: '" + text + "' is not a number");
        }
        return CheckFrameRate(hz);
      }));
}

void SetFrameRate(haptics::v1::InteractRequest::Open& open, double hz) {
  if (hz > 0) open.set_frame_rate_hz(hz);
}

}  // namespace hs::cli

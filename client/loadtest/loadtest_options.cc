#include "client/loadtest/loadtest_options.h"

#include <cmath>

#include "absl/strings/str_cat.h"
#include "client/frame_rate_args.h"
#include "client/loadtest/metrics_scrape.h"
#include "common/net/address.h"

namespace hs::cli {

absl::Status CheckLoadtestOptions(const LoadtestOptions& options) {
  if (options.clients < 1 || options.clients > kMaxLoadClients) {
    return absl::InvalidArgumentError(absl::StrCat("--clients must be 1..", kMaxLoadClients));
  }
  if (options.viewers < 0 || options.viewers > kMaxLoadViewers) {
    return absl::InvalidArgumentError(absl::StrCat("--viewers must be 0..", kMaxLoadViewers));
  }
  if (!(options.duration_s > 0 && options.duration_s <= kMaxLoadSeconds)) {
    return absl::InvalidArgumentError(
        absl::StrCat("--duration must be in (0, ", kMaxLoadSeconds, "] seconds"));
  }
  if (!(options.rate_hz >= 1 && options.rate_hz <= kMaxLoadRateHz)) {
    return absl::InvalidArgumentError(absl::StrCat("--rate must be 1..", kMaxLoadRateHz, " Hz"));
  }
  if (options.frame_rate_hz != 0) {
    if (absl::Status s = CheckFrameRate(options.frame_rate_hz); !s.ok()) return s;
  }
  if (options.step_s != 0 && !(options.step_s >= 1e-4 && options.step_s <= 1)) {
    return absl::InvalidArgumentError("--step-s must be in [0.0001, 1] seconds");
  }
  if (std::llround(options.duration_s * options.rate_hz) < 1) {
    return absl::InvalidArgumentError("--duration x --rate must make at least one pose");
  }
  if (options.planes && !options.needs.Has(Effect::kLocalModel)) {
    return absl::InvalidArgumentError("--planes needs local_model among --needs");
  }
  if (!options.server_metrics_url.empty()) {
    if (absl::Status s = CheckMetricsUrl(options.server_metrics_url); !s.ok()) return s;
  }
  if (!IsLoopbackAddress(options.server.address) && !options.allow_remote) {
    return absl::InvalidArgumentError(options.server.address +
                                      " is not on loopback: give --allow-remote to load it");
  }
  return absl::OkStatus();
}

}  // namespace hs::cli

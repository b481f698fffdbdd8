#include "client/remote/link_schedule.h"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "absl/strings/str_cat.h"

namespace hs::cli {
namespace {

absl::Status CheckIn(const char* name, double value, double high) {
  if (std::isfinite(value) && value >= 0 && value <= high) return absl::OkStatus();
  return absl::InvalidArgumentError(
      absl::StrCat(name, " must be a number in [0, ", high, "], not ", value));
}

// A draw in [0, 1) taken only when `p` could make it count, so that a link
// without losses or stalls draws the same numbers as before they existed.
bool Happens(double p, std::mt19937_64& random) {
  return p > 0 && std::uniform_real_distribution<double>(0, 1)(random) < p;
}

}  // namespace

absl::Status CheckLinkConditions(const LinkConditions& link) {
  for (const auto& [name, value, high] :
       {std::tuple{"latency", link.latency_ms, kMaxLinkMs},
        std::tuple{"jitter", link.jitter_ms, kMaxLinkMs}, std::tuple{"loss", link.loss, 1.0},
        std::tuple{"stall probability", link.stall_prob, 1.0},
        std::tuple{"stall time", link.stall_ms, kMaxLinkMs}}) {
    if (absl::Status s = CheckIn(name, value, high); !s.ok()) return s;
  }
  return absl::OkStatus();
}

LinkSchedule::LinkSchedule(const LinkConditions& link, uint64_t stream)
    : one_way_s_(link.latency_ms / 2e3),
      jitter_s_(link.jitter_ms / 1e3),
      loss_(link.loss),
      stall_prob_(link.stall_ms > 0 ? link.stall_prob : 0),
      stall_s_(link.stall_ms / 1e3),
      random_(link.seed * 2 + stream) {}

std::optional<double> LinkSchedule::Release(double now_s) {
  if (Happens(loss_, random_)) {
    ++lost_;
    return std::nullopt;
  }
  double at = now_s + one_way_s_;
  if (jitter_s_ > 0) at += std::uniform_real_distribution<double>(0, jitter_s_)(random_);
  if (Happens(stall_prob_, random_)) {
    at += stall_s_;
    ++stalled_;
  }
  at = std::max(at, last_at_);  // in order, as on one stream
  last_at_ = at;
  return at;
}

}  // namespace hs::cli

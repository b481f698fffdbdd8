#pragma once
// When a message sent over a simulated link comes out at the other end:
// held the one-way latency plus a random jitter, sometimes lost (as an
// unreliable transport would lose it), sometimes stalled (as a reliable
// stream holds a lost segment until it is sent again), and never before
// the message sent ahead of it, so that a stall holds everything behind
// it. Seeded, so runs repeat. Used by the in-process delay line
// (delay_line.h) and by the TCP relay (client/relay/tcp_relay.h).

#include <cstdint>
#include <optional>
#include <random>

#include "absl/status/status.h"

namespace hs::cli {

/// How a link delays, loses and stalls messages.
struct LinkConditions {
  /// Round trip, milliseconds: each direction holds a message half of it.
  double latency_ms = 0;
  /// Each message is held up to this much longer, milliseconds, uniformly.
  double jitter_ms = 0;
  /// Each message is lost with this probability, in each direction.
  double loss = 0;
  /// Each message is held `stall_ms` longer with this probability, in each
  /// direction, and the ones behind it wait for it.
  double stall_prob = 0;
  double stall_ms = 0;
  uint64_t seed = 1;

  bool ideal() const {
    return latency_ms == 0 && jitter_ms == 0 && loss == 0 && (stall_prob == 0 || stall_ms == 0);
  }
};

/// The longest latency, jitter or stall a link may have, milliseconds.
inline constexpr double kMaxLinkMs = 10000;

/// INVALID_ARGUMENT naming the first field that is not a finite number in
/// its range: times in [0, kMaxLinkMs], probabilities in [0, 1].
absl::Status CheckLinkConditions(const LinkConditions& link);

class LinkSchedule {
 public:
  /// `stream` tells apart the directions (and connections) of one link in
  /// the seed. `link` must pass CheckLinkConditions.
  LinkSchedule(const LinkConditions& link, uint64_t stream);

  /// When a message sent at `now_s` (seconds on the caller's clock, not
  /// decreasing from call to call) comes out; nullopt when it is lost.
  std::optional<double> Release(double now_s);

  int64_t lost() const { return lost_; }
  int64_t stalled() const { return stalled_; }

 private:
  const double one_way_s_, jitter_s_, loss_, stall_prob_, stall_s_;
  std::mt19937_64 random_;
  double last_at_ = 0;
  int64_t lost_ = 0, stalled_ = 0;
};

}  // namespace hs::cli

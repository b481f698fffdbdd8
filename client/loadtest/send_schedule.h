#pragma once
// When the load test's streams send. The devices and the echo baseline
// take turns in short slices of one run, so that both meet the machine in
// the same state: on a shared machine the noise moves from second to
// second, and a baseline measured after the devices met other noise.

#include <chrono>
#include <cstdint>

namespace hs::cli {

/// The send times of one stream's messages.
struct SendSchedule {
  using Clock = std::chrono::steady_clock;
  /// When the first slice begins.
  Clock::time_point start;
  /// Messages per second while the stream's kind has its turn.
  double rate_hz = 1000;
  /// Length of each turn, seconds; 0: no turns, every slice is this kind's.
  double slice_s = 0;
  /// 0: the first slice and every other one after it; 1: the others.
  int turn = 0;

  /// When message `index` (0-based) goes out: `index` / rate_hz into the
  /// stream's own time, which runs only during its turns.
  Clock::time_point At(uint64_t index) const;
  /// Messages sent in one turn (at least 1); every message when no turns.
  uint64_t PerSlice() const;
};

}  // namespace hs::cli

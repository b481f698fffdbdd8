#pragma once
// One stream's messages of `hapticctl loadtest`: when each was sent, the
// round trips of those answered, and the sending on a schedule.

#include <atomic>
#include <cstdint>
#include <functional>
#include <vector>

#include "client/loadtest/send_schedule.h"

namespace hs::cli {

/// The steady clock, nanoseconds: send times and device times.
int64_t SteadyNowNs();

/// Send times of one stream's messages (sequence 1..count) and the round
/// trips of those answered. One writer thread marks sends, one reader
/// thread marks answers.
class RoundTrips {
 public:
  explicit RoundTrips(size_t count);

  void MarkSent(uint64_t sequence);
  /// Every sent message up to `sequence` not answered before is answered
  /// now (a later answer covers the messages it superseded); answers to
  /// messages not sent yet are ignored.
  void MarkAnswered(uint64_t sequence);
  uint64_t sent() const { return sent_.load(std::memory_order_acquire); }
  uint64_t answered() const { return answered_.load(std::memory_order_acquire); }
  size_t count() const { return sent_ns_.size(); }
  /// Round trips in the order answered, milliseconds (read after the
  /// stream is done).
  std::vector<double>& rtt_ms() { return rtt_ms_; }

 private:
  std::vector<int64_t> sent_ns_;
  std::atomic<uint64_t> sent_{0};
  std::atomic<uint64_t> answered_{0};
  std::vector<double> rtt_ms_;
};

/// Sends messages 1..trips.count() at `schedule`'s times through
/// `write(sequence)` (false: the stream ended, and sending stops there),
/// marking each sent just before; then waits up to 2 s for their answers
/// and closes the sending side with `done()`.
void SendPaced(RoundTrips& trips, const SendSchedule& schedule,
               const std::function<bool(uint64_t)>& write, const std::function<void()>& done);

}  // namespace hs::cli

#include "client/loadtest/round_trips.h"

#include <algorithm>
#include <chrono>
#include <thread>

namespace hs::cli {

int64_t SteadyNowNs() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

RoundTrips::RoundTrips(size_t count) : sent_ns_(count, 0) { rtt_ms_.reserve(count); }

void RoundTrips::MarkSent(uint64_t sequence) {
  sent_ns_[sequence - 1] = SteadyNowNs();
  sent_.store(sequence, std::memory_order_release);
}

void RoundTrips::MarkAnswered(uint64_t sequence) {
  const int64_t now = SteadyNowNs();
  sequence = std::min<uint64_t>(sequence, sent_.load(std::memory_order_acquire));
  uint64_t answered = answered_.load(std::memory_order_relaxed);
  for (; answered < sequence; ++answered) {
    rtt_ms_.push_back(1e-6 * static_cast<double>(now - sent_ns_[answered]));
  }
  answered_.store(answered, std::memory_order_release);
}

void SendPaced(RoundTrips& trips, const SendSchedule& schedule,
               const std::function<bool(uint64_t)>& write, const std::function<void()>& done) {
  for (uint64_t i = 0; i < trips.count(); ++i) {
    std::this_thread::sleep_until(schedule.At(i));
    trips.MarkSent(i + 1);
    if (!write(i + 1)) return;
  }
  using Clock = std::chrono::steady_clock;
  const Clock::time_point give_up = Clock::now() + std::chrono::seconds(2);
  while (trips.answered() < trips.count() && Clock::now() < give_up) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  done();
}

}  // namespace hs::cli

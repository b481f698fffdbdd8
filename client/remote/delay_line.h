#pragma once
// One direction of a simulated network link, in process: each message is
// held, lost or stalled as its schedule says (link_schedule.h) and comes
// out in the order it went in (as on one stream).

#include <algorithm>
#include <cstdint>
#include <deque>
#include <mutex>
#include <optional>
#include <utility>

#include "client/remote/link_schedule.h"

namespace hs::cli {

template <typename T>
class DelayLine {
 public:
  /// `stream` tells the two directions of one link apart in the seed.
  DelayLine(const LinkConditions& link, uint64_t stream) : schedule_(link, stream) {}

  /// Sends `item` at `now_s` (seconds on the caller's clock).
  void Push(double now_s, T item) {
    std::lock_guard lock(mutex_);
    const std::optional<double> release = schedule_.Release(now_s);
    if (!release) return;
    const double at = *release;
    delay_sum_s_ += at - now_s;
    delay_max_s_ = std::max(delay_max_s_, at - now_s);
    queue_.emplace_back(at, std::move(item));
  }

  /// Calls `take(item)` for every item due by `now_s`, in order.
  template <typename F>
  void PopDue(double now_s, F&& take) {
    std::unique_lock lock(mutex_);
    while (!queue_.empty() && queue_.front().first <= now_s) {
      T item = std::move(queue_.front().second);
      queue_.pop_front();
      ++delivered_;
      lock.unlock();
      take(std::move(item));
      lock.lock();
    }
  }

  int64_t lost() const {
    std::lock_guard lock(mutex_);
    return schedule_.lost();
  }
  int64_t stalled() const {
    std::lock_guard lock(mutex_);
    return schedule_.stalled();
  }
  /// Mean and largest time a sent message was held, seconds.
  double mean_delay_s() const {
    std::lock_guard lock(mutex_);
    const int64_t sent = static_cast<int64_t>(queue_.size()) + delivered_;
    return sent > 0 ? delay_sum_s_ / sent : 0;
  }
  double max_delay_s() const {
    std::lock_guard lock(mutex_);
    return delay_max_s_;
  }

 private:
  mutable std::mutex mutex_;
  LinkSchedule schedule_;
  std::deque<std::pair<double, T>> queue_;
  double delay_sum_s_ = 0, delay_max_s_ = 0;
  int64_t delivered_ = 0;
};

/// What a link did, both ways.
struct LinkStats {
  /// The mean time a message was held, milliseconds.
  double uplink_mean_ms = 0;
  double downlink_mean_ms = 0;
  int64_t poses_lost = 0;
  int64_t frames_lost = 0;
  /// Messages held by a stall (and the ones behind them with them).
  int64_t poses_stalled = 0;
  int64_t frames_stalled = 0;
};

/// The stats of a link whose poses go on `up` and frames on `down`.
template <typename Pose, typename Frame>
LinkStats StatsOf(const DelayLine<Pose>& up, const DelayLine<Frame>& down) {
  return {.uplink_mean_ms = up.mean_delay_s() * 1e3,
          .downlink_mean_ms = down.mean_delay_s() * 1e3,
          .poses_lost = up.lost(),
          .frames_lost = down.lost(),
          .poses_stalled = up.stalled(),
          .frames_stalled = down.stalled()};
}

}  // namespace hs::cli

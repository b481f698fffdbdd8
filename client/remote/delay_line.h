#pragma once
// One direction of a simulated network link, in process: each message is
// held for the one-way latency plus a random jitter, or lost, and comes out
// in the order it went in (as on one stream). Seeded, so runs repeat.

#include <algorithm>
#include <cstdint>
#include <deque>
#include <mutex>
#include <random>
#include <utility>

namespace hs::cli {

/// How a link delays and loses messages.
struct LinkConditions {
  /// Round trip, milliseconds: each direction holds a message half of it.
  double latency_ms = 0;
  /// Each message is held up to this much longer, milliseconds, uniformly.
  double jitter_ms = 0;
  /// Each message is lost with this probability, in each direction.
  double loss = 0;
  uint64_t seed = 1;

  bool ideal() const { return latency_ms == 0 && jitter_ms == 0 && loss == 0; }
};

template <typename T>
class DelayLine {
 public:
  /// `stream` tells the two directions of one link apart in the seed.
  DelayLine(const LinkConditions& link, uint64_t stream)
      : one_way_s_(link.latency_ms / 2e3),
        jitter_s_(link.jitter_ms / 1e3),
        loss_(link.loss),
        random_(link.seed * 2 + stream) {}

  /// Sends `item` at `now_s` (seconds on the caller's clock).
  void Push(double now_s, T item) {
    std::lock_guard lock(mutex_);
    if (loss_ > 0 && std::uniform_real_distribution<double>(0, 1)(random_) < loss_) {
      ++lost_;
      return;
    }
    double at = now_s + one_way_s_;
    if (jitter_s_ > 0) at += std::uniform_real_distribution<double>(0, jitter_s_)(random_);
    at = std::max(at, last_at_);  // in order, as on one stream
    last_at_ = at;
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
    return lost_;
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
  const double one_way_s_, jitter_s_, loss_;
  mutable std::mutex mutex_;
  std::mt19937_64 random_;
  std::deque<std::pair<double, T>> queue_;
  double last_at_ = 0;
  double delay_sum_s_ = 0, delay_max_s_ = 0;
  int64_t lost_ = 0, delivered_ = 0;
};

}  // namespace hs::cli

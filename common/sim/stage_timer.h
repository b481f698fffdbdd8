#pragma once
// Internal to common/sim: adds the wall time of its scope to one stage's
// statistics.

#include <chrono>

#include "common/sim/step_frame.h"

namespace hs {

class StageTimer {
 public:
  explicit StageTimer(StageStats& stats)
      : stats_(stats), start_(std::chrono::steady_clock::now()) {}
  ~StageTimer() {
    ++stats_.runs;
    stats_.total_ns += std::chrono::duration_cast<std::chrono::nanoseconds>(
                           std::chrono::steady_clock::now() - start_)
                           .count();
  }
  StageTimer(const StageTimer&) = delete;
  StageTimer& operator=(const StageTimer&) = delete;

 private:
  StageStats& stats_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace hs

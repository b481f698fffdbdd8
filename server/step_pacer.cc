#include "server/step_pacer.h"

#include <algorithm>

namespace hs {

StepPacer::StepPacer(int64_t period_ns, int64_t now_ns, int64_t cpu_ns)
    : period_ns_(period_ns),
      last_start_ns_(now_ns),
      cpu_at_last_start_ns_(cpu_ns),
      deadline_ns_(now_ns + period_ns) {}

StepPacer::Start StepPacer::StepStarts(int64_t now_ns, int64_t cpu_ns, bool devices_clocked) {
  Start start;
  const int64_t lag_ns = now_ns - deadline_ns_;  // negative when the devices came first
  start.lag_ns = std::max<int64_t>(lag_ns, 0);
  if (lag_ns > period_ns_) {
    start.missed = lag_ns / period_ns_;
    start.off_cpu = cpu_ns - cpu_at_last_start_ns_ < period_ns_ && last_step_ns_ < period_ns_;
    deadline_ns_ += start.missed * period_ns_;
  }
  last_start_ns_ = now_ns;
  cpu_at_last_start_ns_ = cpu_ns;
  deadline_ns_ = devices_clocked ? now_ns + period_ns_ + period_ns_ / 4 : deadline_ns_ + period_ns_;
  return start;
}

}  // namespace hs

#include "client/loadtest/send_schedule.h"

#include <algorithm>
#include <cmath>

namespace hs::cli {
namespace {

SendSchedule::Clock::duration Seconds(double s) {
  return std::chrono::duration_cast<SendSchedule::Clock::duration>(
      std::chrono::duration<double>(s));
}

}  // namespace

uint64_t SendSchedule::PerSlice() const {
  if (slice_s <= 0) return UINT64_MAX;
  return std::max<uint64_t>(1, static_cast<uint64_t>(std::floor(rate_hz * slice_s)));
}

SendSchedule::Clock::time_point SendSchedule::At(uint64_t index) const {
  const uint64_t per_slice = PerSlice();
  const uint64_t slice = index / per_slice;
  const uint64_t within = index % per_slice;
  return start + Seconds(static_cast<double>(2 * slice + turn) * slice_s +
                         static_cast<double>(within) / rate_hz);
}

}  // namespace hs::cli

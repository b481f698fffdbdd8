#include "client/loadtest/send_schedule.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>

namespace hs::cli {
namespace {

using Clock = SendSchedule::Clock;

double SecondsAfter(Clock::time_point start, Clock::time_point t) {
  return std::chrono::duration<double>(t - start).count();
}

// Without turns a stream sends at its rate from the start, message after
// message.
TEST(SendScheduleTest, NoTurnsIsPlainRate) {
  const SendSchedule s{.start = Clock::now(), .rate_hz = 1000, .slice_s = 0, .turn = 0};
  EXPECT_NEAR(SecondsAfter(s.start, s.At(0)), 0.0, 1e-9);
  EXPECT_NEAR(SecondsAfter(s.start, s.At(1)), 0.001, 1e-9);
  EXPECT_NEAR(SecondsAfter(s.start, s.At(12345)), 12.345, 2e-9);  // whole ns
}

// With turns, every message of each kind falls inside one of its own
// slices, at the rate within the slice; the two kinds never share a slice,
// and each sends as many messages per slice.
TEST(SendScheduleTest, TurnsNeverOverlap) {
  const Clock::time_point start = Clock::now();
  for (const double rate : {1.0, 3.0, 200.0, 1000.0, 5000.0}) {
    const SendSchedule devices{.start = start, .rate_hz = rate, .slice_s = 0.5, .turn = 0};
    SendSchedule echo = devices;
    echo.turn = 1;
    EXPECT_EQ(devices.PerSlice(), echo.PerSlice());
    for (uint64_t i = 0; i < 3 * devices.PerSlice(); ++i) {
      for (const SendSchedule* s : {&devices, static_cast<const SendSchedule*>(&echo)}) {
        const double t = SecondsAfter(start, s->At(i));
        // The clock counts whole nanoseconds: times are off by up to 1 ns.
        const auto slice = static_cast<int>(std::floor((t + 2e-9) / 0.5));
        EXPECT_EQ(slice % 2, s->turn) << "rate " << rate << " message " << i;
        const double within = t - slice * 0.5;
        EXPECT_NEAR(within, static_cast<double>(i % s->PerSlice()) / rate, 2e-9);
        if (i > 0) {
          EXPECT_GT(s->At(i), s->At(i - 1));
        }
      }
    }
  }
}

}  // namespace
}  // namespace hs::cli

#include "client/loadtest/turn_cpu.h"

#include <gtest/gtest.h>

#include <condition_variable>
#include <mutex>

namespace hs::cli {
namespace {

// Readers that count up by one second per reading (the server's and the
// client's alike), so that each turn's totals are its count of intervals;
// the server's reading number `fail_at` fails. Tests wait on `readings`.
class CountingReaders {
 public:
  explicit CountingReaders(int fail_at = -1) : fail_at_(fail_at) {}
  CpuReaders Readers() {
    return {.server = [this]() -> std::optional<double> {
              const int n = Next();
              if (n == fail_at_) return std::nullopt;
              return n;
            },
            .client = [this] { return static_cast<double>(client_++); }};
  }
  void WaitFor(int count) {
    std::unique_lock lock(mu_);
    cv_.wait(lock, [&] { return readings_ >= count; });
  }

 private:
  int Next() {
    std::lock_guard lock(mu_);
    const int n = readings_++;
    cv_.notify_all();
    return n;
  }
  const int fail_at_;
  std::mutex mu_;
  std::condition_variable cv_;
  int readings_ = 0;
  int client_ = 0;
};

// Without turns everything falls in the devices' turn: one interval, from
// the start to Stop.
TEST(TurnCpuTest, NoTurnsOneInterval) {
  CountingReaders readers;
  TurnCpu cpu(readers.Readers(), {.start = SendSchedule::Clock::now(), .slice_s = 0});
  readers.WaitFor(1);  // the start's reading
  const TurnTotals totals = cpu.Stop();
  EXPECT_EQ(*totals.server_s[0], 1);
  EXPECT_EQ(totals.client_s[0], 1);
  EXPECT_GE(totals.wall_s[0], 0);
  EXPECT_EQ(*totals.server_s[1], 0);
  EXPECT_EQ(totals.wall_s[1], 0);
}

// With turns the intervals alternate between the two kinds: after the
// start's reading and five boundaries, the devices had at least three
// intervals (slices 0, 2, 4) and the echo two (1, 3); more may pass before
// Stop, still alternating. The readers' counts agree turn by turn.
TEST(TurnCpuTest, TurnsAlternate) {
  CountingReaders readers;
  TurnCpu cpu(readers.Readers(), {.start = SendSchedule::Clock::now(), .slice_s = 1e-3});
  readers.WaitFor(6);
  const TurnTotals totals = cpu.Stop();
  EXPECT_EQ(*totals.server_s[0] - totals.client_s[0], 0);
  EXPECT_GE(totals.client_s[0], 3);
  EXPECT_GE(totals.client_s[1], 2);
  EXPECT_LE(totals.client_s[0] - totals.client_s[1], 1);
  EXPECT_GE(totals.client_s[1] - totals.client_s[0], -1);
  EXPECT_GT(totals.wall_s[0], 0);
  EXPECT_GT(totals.wall_s[1], 0);
}

// A failed server reading makes the server's figure unknown for the turns
// it touches, and only for those; the client's counts on.
TEST(TurnCpuTest, FailedReadingUnknownInItsTurns) {
  CountingReaders readers(/*fail_at=*/0);  // the start's reading: slice 0
  TurnCpu cpu(readers.Readers(), {.start = SendSchedule::Clock::now(), .slice_s = 1e-3});
  readers.WaitFor(4);
  const TurnTotals totals = cpu.Stop();
  EXPECT_FALSE(totals.server_s[0].has_value());
  EXPECT_TRUE(totals.server_s[1].has_value());
  EXPECT_GE(totals.client_s[0], 2);
}

// Stopped before the start, nothing is read.
TEST(TurnCpuTest, StoppedBeforeTheStart) {
  CountingReaders readers;
  TurnCpu cpu(readers.Readers(), {.start = SendSchedule::Clock::now() + std::chrono::hours(1)});
  const TurnTotals totals = cpu.Stop();
  EXPECT_EQ(totals.wall_s[0], 0);
  EXPECT_EQ(*totals.server_s[0], 0);
}

}  // namespace
}  // namespace hs::cli

#include "server/priority_inheriting_mutex.h"

#include <gtest/gtest.h>
#include <pthread.h>
#include <sched.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <thread>

#include "server/thread_priority.h"

namespace hs {
namespace {

using Clock = std::chrono::steady_clock;

TEST(PriorityInheritingMutexTest, ExcludesLikeAMutex) {
  PriorityInheritingMutex mutex;
  int64_t count = 0;
  auto add = [&] {
    for (int i = 0; i < 100000; ++i) {
      std::lock_guard lock(mutex);
      ++count;
    }
  };
  std::thread other(add);
  add();
  other.join();
  EXPECT_EQ(count, 200000);

  std::unique_lock held(mutex);
  bool taken_meanwhile = true;
  std::thread([&] { taken_meanwhile = mutex.try_lock(); }).join();
  EXPECT_FALSE(taken_meanwhile);
  held.unlock();
  std::thread([&] {
    taken_meanwhile = mutex.try_lock();
    if (taken_meanwhile) mutex.unlock();
  }).join();
  EXPECT_TRUE(taken_meanwhile);
}

// Puts the calling thread under SCHED_FIFO at `priority`, then on CPU 0
// (in that order: under the default scheduler it would wait there behind
// the real-time threads until their throttling lets it run).
bool RunOnCpu0At(int priority) {
  cpu_set_t cpus;
  CPU_ZERO(&cpus);
  CPU_SET(0, &cpus);
  return SetRealtimePriority(priority).ok() &&
         pthread_setaffinity_np(pthread_self(), sizeof cpus, &cpus) == 0;
}

// The classic inversion, on one CPU: a low-priority thread holds the mutex,
// a middle one spins for `kSpin`, a high one wants the mutex. How long the
// high one waits: with inheritance, the holder runs above the spinner and
// lets go at once; without, not before the spinner stops. Returns a
// negative duration when the system refuses real-time scheduling.
constexpr auto kSpin = std::chrono::milliseconds(300);

template <typename Mutex>
Clock::duration HighPriorityWait() {
  Mutex mutex;
  std::atomic<bool> held = false, spinning = false, refused = false;
  Clock::duration waited{-1};
  std::thread low([&] {
    if (!RunOnCpu0At(1)) refused = true;
    std::lock_guard lock(mutex);
    held = true;
    // Lets go only once it has run after the spinner started.
    while (!spinning && !refused) {
    }
  });
  while (!held && !refused) std::this_thread::yield();
  std::thread middle([&] {
    if (!RunOnCpu0At(5)) refused = true;
    spinning = true;
    const Clock::time_point end = Clock::now() + kSpin;
    while (Clock::now() < end) {
    }
  });
  while (!spinning && !refused) std::this_thread::yield();
  std::thread high([&] {
    if (!RunOnCpu0At(10)) {
      refused = true;
      return;
    }
    const Clock::time_point start = Clock::now();
    std::lock_guard lock(mutex);
    waited = Clock::now() - start;
  });
  high.join();
  middle.join();
  low.join();
  return refused ? Clock::duration{-1} : waited;
}

TEST(PriorityInheritingMutexTest, HolderRunsAtTheWaitersPriority) {
  if (!CheckRealtimePriority(10).ok()) GTEST_SKIP() << "no real-time scheduling here";
  if (std::thread::hardware_concurrency() < 2) GTEST_SKIP() << "needs a second CPU";
  // A plain mutex shows the inversion the test is built to catch.
  const Clock::duration plain = HighPriorityWait<std::mutex>();
  const Clock::duration inheriting = HighPriorityWait<PriorityInheritingMutex>();
  ASSERT_GE(plain.count(), 0);
  ASSERT_GE(inheriting.count(), 0);
  EXPECT_GE(plain, kSpin * 3 / 4);
  EXPECT_LT(inheriting, kSpin / 3);
}

}  // namespace
}  // namespace hs

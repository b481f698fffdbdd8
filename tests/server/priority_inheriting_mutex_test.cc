#include "server/priority_inheriting_mutex.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <thread>
#include <vector>

#include "server/thread_priority.h"
#include "tests/server/realtime_on_cpu.h"

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

// The classic inversion, on one CPU: a low-priority thread holds the mutex,
// a middle one spins for 300 ms, a high one wants the mutex. With
// inheritance the holder runs above the spinner and lets go at once: the
// high one has the mutex before the spin ends; without, not before.
struct Inversion {
  bool refused = false;  // the system refused real-time scheduling or the CPU
  Clock::time_point acquired, spin_ended;
};

template <typename Mutex>
Inversion RunInversion(int cpu) {
  Mutex mutex;
  std::atomic<bool> held = false, spinning = false, refused = false;
  Inversion result;
  std::thread low([&] {
    if (!testing::RunOnCpuAt(cpu, 1)) refused = true;
    std::lock_guard lock(mutex);
    held = true;
    // Lets go only once it has run after the spinner started.
    while (!spinning && !refused) {
    }
  });
  while (!held && !refused) std::this_thread::yield();
  std::thread middle([&] {
    if (!testing::RunOnCpuAt(cpu, 5)) refused = true;
    spinning = true;
    const Clock::time_point end = Clock::now() + std::chrono::milliseconds(300);
    while (Clock::now() < end) {
    }
    result.spin_ended = Clock::now();
  });
  while (!spinning && !refused) std::this_thread::yield();
  std::thread high([&] {
    if (!testing::RunOnCpuAt(cpu, 10)) {
      refused = true;
      return;
    }
    std::lock_guard lock(mutex);
    result.acquired = Clock::now();
  });
  high.join();
  middle.join();
  low.join();
  result.refused = refused;
  return result;
}

TEST(PriorityInheritingMutexTest, HolderRunsAtTheWaitersPriority) {
  if (!CheckRealtimePriority(10).ok()) GTEST_SKIP() << "no real-time scheduling here";
  // One CPU for the three threads, another for this one, which starts them.
  const std::vector<int> cpus = testing::AllowedCpus();
  if (cpus.size() < 2) GTEST_SKIP() << "needs a second CPU";
  const int cpu = cpus.front();
  // A plain mutex shows the inversion the test is built to catch.
  const Inversion plain = RunInversion<std::mutex>(cpu);
  const Inversion inheriting = RunInversion<PriorityInheritingMutex>(cpu);
  if (plain.refused || inheriting.refused) GTEST_SKIP() << "real-time scheduling refused";
  EXPECT_GE(plain.acquired, plain.spin_ended);
  EXPECT_LT(inheriting.acquired, inheriting.spin_ended);
}

}  // namespace
}  // namespace hs

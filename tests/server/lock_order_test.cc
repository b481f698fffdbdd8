#include "server/lock_order.h"

#include <gtest/gtest.h>

#include <mutex>
#include <thread>

#include "server/priority_inheriting_mutex.h"

namespace hs {
namespace {

// Locks taken in rising level, let go in any order, and taken again, pass;
// leaves go anywhere; each thread has its own account.
TEST(LockOrderTest, RisingLevelsPass) {
  PriorityInheritingMutex scene(LockLevel::kScene), streams(LockLevel::kStreams),
      wake(LockLevel::kWake), leaf;
  {
    std::unique_lock a(scene);
    std::unique_lock b(streams);
    std::lock_guard c(leaf);
    a.unlock();  // out of order
    std::lock_guard d(wake);
  }
  std::lock_guard again(streams);
  std::thread([&] { std::lock_guard other_thread(scene); }).join();
}

// Taking a lower or equal level while holding a higher one aborts, naming
// both levels.
TEST(LockOrderDeathTest, FallingLevelAborts) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  PriorityInheritingMutex scene(LockLevel::kScene), streams(LockLevel::kStreams);
  EXPECT_DEATH(
      {
        std::lock_guard a(streams);
        std::lock_guard b(scene);
      },
      "taking a lock of level 10 while holding one of level 20");
  PriorityInheritingMutex frames_a(LockLevel::kFrames), frames_b(LockLevel::kFrames);
  EXPECT_DEATH(
      {
        std::lock_guard a(frames_a);
        std::lock_guard b(frames_b);
      },
      "level 30 while holding one of level 30");
}

}  // namespace
}  // namespace hs

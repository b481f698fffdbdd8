#include "common/model/coin_lock.h"

#include <gtest/gtest.h>

#include <Inventor/SoDB.h>

#include <atomic>
#include <thread>
#include <vector>

namespace hs {
namespace {

// Coin is initialized once, whoever asks first and however often.
TEST(CoinLockTest, InitializesCoinOnce) {
  InitCoinOnce();
  EXPECT_TRUE(SoDB::isInitialized());
  InitCoinOnce();
  { const std::unique_lock<std::mutex> lock = LockCoin(); }
  EXPECT_TRUE(SoDB::isInitialized());
}

// The lock is one for the process: threads that take it never overlap.
TEST(CoinLockTest, OneHolderAtATime) {
  std::atomic<int> inside{0};
  std::atomic<int> most{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < 8; ++t) {
    threads.emplace_back([&] {
      for (int i = 0; i < 200; ++i) {
        const std::unique_lock<std::mutex> lock = LockCoin();
        ASSERT_TRUE(lock.owns_lock());
        const int now = ++inside;
        int seen = most.load();
        while (now > seen && !most.compare_exchange_weak(seen, now)) {
        }
        std::this_thread::yield();
        --inside;
      }
    });
  }
  for (std::thread& t : threads) t.join();
  EXPECT_EQ(most.load(), 1);
}

}  // namespace
}  // namespace hs

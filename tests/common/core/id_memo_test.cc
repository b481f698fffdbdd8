#include "common/core/id_memo.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace hs {
namespace {

// Against a brute-force oracle: over random resets of random sizes and
// random lookups, each id's value is computed once per reset, and every
// lookup returns the value computed for it since the last reset (Find: or
// none before it is).
TEST(IdMemoTest, ComputesEachIdOnceBetweenResets) {
  std::mt19937 random(7);
  IdMemo<int> memo;
  int next_value = 0;
  for (int round = 0; round < 50; ++round) {
    const int size = std::uniform_int_distribution<int>(1, 64)(random);
    memo.Reset(size);
    std::vector<int> expected(size, -1);  // -1: not computed since the reset
    std::vector<int> computed(size, 0);
    for (int lookup = 0; lookup < 200; ++lookup) {
      const int id = std::uniform_int_distribution<int>(0, size - 1)(random);
      // Find sees only the values computed since the reset.
      const int* found = memo.Find(id);
      ASSERT_EQ(found != nullptr, expected[id] >= 0);
      if (found) EXPECT_EQ(*found, expected[id]);
      const int value = memo.Get(id, [&] {
        ++computed[id];
        return next_value++;
      });
      if (expected[id] < 0) expected[id] = value;
      EXPECT_EQ(value, expected[id]);
      EXPECT_EQ(memo.data()[id], value);
    }
    for (int id = 0; id < size; ++id) EXPECT_EQ(computed[id], expected[id] < 0 ? 0 : 1);
  }
}

// A reset to a smaller size forgets the values beyond it too: growing back
// computes them again.
TEST(IdMemoTest, ValuesBeforeAResetAreForgottenWhateverTheSize) {
  IdMemo<int> memo;
  memo.Reset(10);
  EXPECT_EQ(memo.Get(9, [] { return 1; }), 1);
  memo.Reset(5);
  memo.Reset(10);
  EXPECT_EQ(memo.Get(9, [] { return 2; }), 2);
}

}  // namespace
}  // namespace hs

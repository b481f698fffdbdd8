#include "client/sdk/triple_buffer.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <thread>

namespace hs::sdk {
namespace {

TEST(TripleBufferTest, ReaderGetsTheNewestValueOnce) {
  // Take finds nothing before a Publish, the newest of several after, and
  // nothing again until the next Publish.
  TripleBuffer<int> buffer;
  EXPECT_FALSE(buffer.Take());
  for (int v : {1, 2, 3}) {
    buffer.back() = v;
    buffer.Publish();
  }
  ASSERT_TRUE(buffer.Take());
  EXPECT_EQ(buffer.front(), 3);
  EXPECT_FALSE(buffer.Take());
  EXPECT_EQ(buffer.front(), 3);
  buffer.back() = 4;
  buffer.Publish();
  ASSERT_TRUE(buffer.Take());
  EXPECT_EQ(buffer.front(), 4);
}

struct Pair {
  int64_t a = 0;
  int64_t b = 0;
};

TEST(TripleBufferTest, ConcurrentReaderSeesWholeIncreasingValues) {
  // A writer publishing (k, -k) for k = 1..200000 while a reader takes:
  // every value taken is whole (never half of one write and half of
  // another) and none is older than the one taken before.
  TripleBuffer<Pair> buffer;
  constexpr int64_t kWrites = 200000;
  std::thread writer([&] {
    for (int64_t k = 1; k <= kWrites; ++k) {
      buffer.back() = {k, -k};
      buffer.Publish();
    }
  });
  int64_t last = 0;
  int64_t torn = 0, backwards = 0;
  while (last < kWrites) {
    if (!buffer.Take()) continue;
    const Pair& p = buffer.front();
    if (p.a != -p.b) ++torn;
    if (p.a < last) ++backwards;
    last = p.a;
  }
  writer.join();
  EXPECT_EQ(torn, 0);
  EXPECT_EQ(backwards, 0);
}

}  // namespace
}  // namespace hs::sdk

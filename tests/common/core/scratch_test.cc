#include "common/core/scratch.h"

#include <gtest/gtest.h>

#include <thread>
#include <vector>

namespace hs {
namespace {

struct Numbers {
  std::vector<int> values;
};
struct OtherNumbers {
  std::vector<int> values;
};

// One object per type and space: asked again, the same one; another type,
// another object.
TEST(ScratchTest, OneObjectPerTypeAndSpace) {
  ScratchSpace space;
  Numbers& first = space.Get<Numbers>();
  first.values.push_back(7);
  EXPECT_EQ(&space.Get<Numbers>(), &first);
  EXPECT_EQ(space.Get<Numbers>().values, std::vector<int>{7});
  EXPECT_NE(static_cast<void*>(&space.Get<OtherNumbers>()), static_cast<void*>(&first));
  EXPECT_TRUE(space.Get<OtherNumbers>().values.empty());
  ScratchSpace other;
  EXPECT_NE(&other.Get<Numbers>(), &first);
}

// A bound space is current until its scope ends; scopes nest, and without
// one each thread has its own.
TEST(ScratchTest, ScopesBindAndNest) {
  Numbers* own = &Scratch<Numbers>();
  ScratchSpace outer, inner;
  {
    const ScratchScope bind_outer(outer);
    EXPECT_EQ(&Scratch<Numbers>(), &outer.Get<Numbers>());
    {
      const ScratchScope bind_inner(inner);
      EXPECT_EQ(&Scratch<Numbers>(), &inner.Get<Numbers>());
    }
    EXPECT_EQ(&Scratch<Numbers>(), &outer.Get<Numbers>());
  }
  EXPECT_EQ(&Scratch<Numbers>(), own);
  Numbers* on_other_thread = nullptr;
  std::thread([&] { on_other_thread = &Scratch<Numbers>(); }).join();
  EXPECT_NE(on_other_thread, own);
}

// What a scene's step relies on: a part that binds its space finds the
// same buffers whichever thread runs it, grown as the last run left them.
TEST(ScratchTest, BoundSpaceFollowsTheWorkAcrossThreads) {
  ScratchSpace part;
  auto run = [&part](int size) {
    const ScratchScope bind(part);
    std::vector<int>& buffer = Scratch<Numbers>().values;
    buffer.resize(size);
    return buffer.capacity();
  };
  const size_t grown = run(1000);
  size_t on_other_thread = 0;
  std::thread([&] { on_other_thread = run(10); }).join();
  EXPECT_EQ(on_other_thread, grown);  // no new buffer: the part's own
}

}  // namespace
}  // namespace hs

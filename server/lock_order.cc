#include "server/lock_order.h"

#include <array>
#include <cstdio>
#include <cstdlib>

#include "common/core/check.h"

namespace hs {
namespace {

// The levels the calling thread holds, in the order taken. Runtime locks
// nest at most four deep; eight leaves room for a mistake to be reported
// rather than overflow.
struct HeldLevels {
  std::array<LockLevel, 8> levels{};
  int count = 0;
};

thread_local HeldLevels held;

}  // namespace

void LockOrderAcquire(LockLevel level) {
  if (level == LockLevel::kLeaf) return;
  if (held.count > 0 && held.levels[held.count - 1] >= level) {
    std::fprintf(stderr, "lock order: taking a lock of level %d while holding one of level %d\n",
                 static_cast<int>(level), static_cast<int>(held.levels[held.count - 1]));
    std::abort();
  }
  HS_CHECK(held.count < static_cast<int>(held.levels.size()));
  held.levels[held.count++] = level;
}

void LockOrderRelease(LockLevel level) {
  if (level == LockLevel::kLeaf) return;
  // unique_lock and condition variables may let go out of order: remove
  // the latest entry of this level.
  for (int i = held.count - 1; i >= 0; --i) {
    if (held.levels[i] != level) continue;
    for (int j = i; j + 1 < held.count; ++j) held.levels[j] = held.levels[j + 1];
    --held.count;
    return;
  }
  HS_CHECK(false && "released a lock level the thread does not hold");
}

}  // namespace hs

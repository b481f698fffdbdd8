#include "server/snapshot_pool.h"

#include <gtest/gtest.h>

#include <set>
#include <vector>

namespace hs {
namespace {

// With no one else holding them, the initial snapshots are taken in turn,
// round and round, and the pool does not grow.
TEST(SnapshotPoolTest, FreeSnapshotsAreTakenInTurn) {
  SnapshotPool pool;
  std::vector<const StepSnapshot*> first_round;
  for (size_t k = 0; k < SnapshotPool::kInitialSlots; ++k) {
    first_round.push_back(pool.Take().snapshot.get());
  }
  EXPECT_EQ(std::set<const StepSnapshot*>(first_round.begin(), first_round.end()).size(),
            SnapshotPool::kInitialSlots);
  for (size_t k = 0; k < SnapshotPool::kInitialSlots; ++k) {
    EXPECT_EQ(pool.Take().snapshot.get(), first_round[k]) << k;
  }
  EXPECT_EQ(pool.size(), SnapshotPool::kInitialSlots);
}

// A snapshot a stream still holds is never handed out; when all are held
// the pool grows by one, and a released one is taken again before growing.
TEST(SnapshotPoolTest, HeldSnapshotsAreSkippedAndThePoolGrows) {
  SnapshotPool pool;
  std::vector<std::shared_ptr<StepSnapshot>> held;
  for (size_t k = 0; k < SnapshotPool::kInitialSlots + 3; ++k) {
    SnapshotPool::Slot& slot = pool.Take();
    for (const auto& other : held) ASSERT_NE(slot.snapshot, other) << k;
    held.push_back(slot.snapshot);
  }
  EXPECT_EQ(pool.size(), SnapshotPool::kInitialSlots + 3);
  const StepSnapshot* released = held[4].get();
  held.erase(held.begin() + 4);
  EXPECT_EQ(pool.Take().snapshot.get(), released);
  EXPECT_EQ(pool.size(), SnapshotPool::kInitialSlots + 3);
}

// Past kMaxPooled held snapshots the pool stops growing: each Take gives a
// fresh snapshot the pool does not keep.
TEST(SnapshotPoolTest, GrowthStopsAtTheCap) {
  SnapshotPool pool;
  std::vector<std::shared_ptr<StepSnapshot>> held;
  for (size_t k = 0; k < SnapshotPool::kMaxPooled; ++k) held.push_back(pool.Take().snapshot);
  EXPECT_EQ(pool.size(), SnapshotPool::kMaxPooled);
  const std::shared_ptr<StepSnapshot> a = pool.Take().snapshot;
  const std::shared_ptr<StepSnapshot> b = pool.Take().snapshot;
  EXPECT_NE(a, b);
  for (const auto& s : held) {
    EXPECT_NE(s, a);
    EXPECT_NE(s, b);
  }
  EXPECT_EQ(pool.size(), SnapshotPool::kMaxPooled);
  // Releasing a pooled one makes it the next taken.
  const StepSnapshot* released = held.back().get();
  held.pop_back();
  EXPECT_EQ(pool.Take().snapshot.get(), released);
}

// A slot taken again is the same slot: its snapshot is written over, and
// the frame storage kept for it is still there.
TEST(SnapshotPoolTest, SlotsKeepTheirSnapshotAndStorage) {
  SnapshotPool pool;
  SnapshotPool::Slot& slot = pool.Take();
  slot.snapshot->step = 41;
  slot.storage.most_points = 7;
  const StepSnapshot* snapshot = slot.snapshot.get();
  for (size_t k = 1; k < SnapshotPool::kInitialSlots; ++k) pool.Take();
  SnapshotPool::Slot& again = pool.Take();
  EXPECT_EQ(&again, &slot);
  EXPECT_EQ(again.snapshot.get(), snapshot);
  EXPECT_EQ(again.snapshot->step, 41);
  EXPECT_EQ(again.storage.most_points, 7u);
}

}  // namespace
}  // namespace hs

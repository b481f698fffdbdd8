#include "common/sim/pair_caches.h"

#include <gtest/gtest.h>

#include <vector>

#include "common/collision/triangle_pairs.h"
#include "common/model/procedural.h"
#include "tests/common/sim/at_pose.h"

namespace hs {
namespace {

// Gives `cache` a region: a query of two touching boxes through it.
void Warm(PairCache& cache) {
  static const HapticObject box = *HapticObject::Create("box", MakeBox(Vector3d::Ones()));
  static const CollisionModel model(box, BvType::kObbRss, 1e-6);
  std::vector<TrianglePair> pairs;
  FindIntersectingTriangles(model, Isometry3d::Identity(), model, At(0.9, 0, 0), 1e-6, pairs, {},
                            &cache);
  ASSERT_GT(cache.regions(), 0);
}

// Within a step each object has one cache, the same however often it is
// asked for, and every pair asked for is held.
TEST(PairCachesTest, OneCachePerObject) {
  PairCaches caches;
  PairCache& a = caches.For(3);
  PairCache& b = caches.For(7);
  EXPECT_NE(&a, &b);
  EXPECT_EQ(&caches.For(7), &b);
  EXPECT_EQ(caches.held(), 2);
}

// A pair left out of a step loses its cache at the step's end; a pair used
// keeps its own, regions and all.
TEST(PairCachesTest, UnusedCachesAreFreedAtTheStepsEnd) {
  PairCaches caches;
  Warm(caches.For(1));
  Warm(caches.For(2));
  caches.FreeUnused();
  EXPECT_EQ(caches.held(), 2);  // both used in the step that ended
  const int regions = caches.For(2).regions();
  caches.FreeUnused();  // only 2 used
  EXPECT_EQ(caches.held(), 1);
  EXPECT_EQ(caches.For(2).regions(), regions);
  caches.FreeUnused();
  caches.FreeUnused();  // no pair in this step
  EXPECT_EQ(caches.held(), 0);
}

// A new pair takes a freed cache, emptied of the old pair's regions, before
// any new one is made.
TEST(PairCachesTest, NewPairsTakeFreedCachesEmpty) {
  PairCaches caches;
  PairCache* old = &caches.For(1);
  Warm(*old);
  caches.FreeUnused();
  caches.FreeUnused();  // object 1 unused: freed
  PairCache& reused = caches.For(5);
  EXPECT_EQ(&reused, old);
  EXPECT_EQ(reused.regions(), 0);
  EXPECT_EQ(caches.held(), 1);
}

}  // namespace
}  // namespace hs

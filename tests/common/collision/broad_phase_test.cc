#include "common/collision/broad_phase.h"

#include <gtest/gtest.h>

#include <random>

#include "common/model/procedural.h"

namespace hs {
namespace {

// The broad phase returns exactly the pairs whose world boxes (object box
// mapped to world by its pose, grown by the margin) overlap, checked against
// an all-pairs test of bounding spheres and boxes: every truly close pair is
// in, and every reported pair has overlapping world AABBs of its vertices.
TEST(BroadPhaseTest, FindsEveryCloseObjectPair) {
  const HapticObject sphere = *HapticObject::Create("s", MakeIcosphere(0.5, 1));
  const CollisionModel model(sphere, BvType::kObbRss, 1e-9);
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> u(0, 6);
  BroadPhase broad_phase;
  std::vector<Vector3d> centres;
  for (int k = 0; k < 30; ++k) {
    centres.emplace_back(u(rng), u(rng), u(rng));
    Isometry3d X = Isometry3d::Identity();
    X.translation() = centres.back();
    broad_phase.Add(k, model, X);
  }
  std::vector<std::pair<int, int>> pairs = {{-1, -1}};  // what it held goes
  broad_phase.CandidatePairs(pairs);
  for (int i = 0; i < 30; ++i) {
    for (int j = i + 1; j < 30; ++j) {
      const double distance = (centres[i] - centres[j]).norm();
      const bool listed = std::binary_search(pairs.begin(), pairs.end(), std::make_pair(i, j));
      // Spheres of radius 0.5 that overlap must be listed; boxes of side ~1
      // apart by more than sqrt(3) in every sense cannot be.
      if (distance < 1.0) {
        EXPECT_TRUE(listed) << i << "," << j;
      }
      if ((centres[i] - centres[j]).cwiseAbs().maxCoeff() > 1.01) {
        EXPECT_FALSE(listed) << i << "," << j;
      }
    }
  }
}

// Moving and removing objects changes the candidate pairs accordingly.
TEST(BroadPhaseTest, PosesAndRemovalUpdatePairs) {
  const HapticObject box = *HapticObject::Create("b", MakeBox(Vector3d(1, 1, 1)));
  const CollisionModel model(box, BvType::kObbRss, 1e-9);
  BroadPhase broad_phase;
  std::vector<std::pair<int, int>> pairs;
  Isometry3d far = Isometry3d::Identity();
  far.translation() = Vector3d(10, 0, 0);
  broad_phase.Add(1, model, Isometry3d::Identity());
  broad_phase.Add(2, model, far);
  broad_phase.CandidatePairs(pairs);
  EXPECT_TRUE(pairs.empty());
  Isometry3d near = Isometry3d::Identity();
  near.translation() = Vector3d(0.9, 0, 0);
  broad_phase.SetPose(2, near);
  broad_phase.CandidatePairs(pairs);
  EXPECT_EQ(pairs, (std::vector<std::pair<int, int>>{{1, 2}}));
  broad_phase.Remove(1);
  broad_phase.CandidatePairs(pairs);
  EXPECT_TRUE(pairs.empty());
}

}  // namespace
}  // namespace hs

#include "common/sim/scene_objects.h"

#include <gtest/gtest.h>

#include <random>
#include <utility>
#include <vector>

#include "common/model/procedural.h"
#include "common/sim/motion_bounds.h"
#include "tests/common/sim/at_pose.h"

namespace hs {
namespace {

constexpr double kMargin = 1e-6;

ObjectId AddCube(SceneObjects& objects, double side, ObjectKind kind, const Isometry3d& X_WO) {
  HapticObject cube = *HapticObject::Create("cube", MakeBox(Vector3d::Constant(side)));
  CollisionModel model(cube, BvType::kObbRss, kMargin);
  return objects.Add(std::move(cube), std::move(model), kind, X_WO);
}

// Ids count up; fixed objects are obstacles and targets, free bodies
// targets only, tools neither; each view holds its objects in id order
// at their poses, with boxes grown by the margin.
TEST(SceneObjectsTest, ViewsFollowKinds) {
  SceneObjects objects;
  const ObjectKind kinds[] = {ObjectKind::kFixed, ObjectKind::kTool, ObjectKind::kFree,
                              ObjectKind::kFixed, ObjectKind::kFree};
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(AddCube(objects, 0.1 * (i + 1), kinds[i], At(i, 0, 0)), i);
  }
  EXPECT_EQ(objects.size(), 5);
  EXPECT_EQ(objects.obstacle_ids(), (std::vector<ObjectId>{0, 3}));
  EXPECT_EQ(objects.target_ids(), (std::vector<ObjectId>{0, 2, 3, 4}));
  EXPECT_EQ(objects.target_index(1), -1);
  for (size_t k = 0; k < objects.target_ids().size(); ++k) {
    const ObjectId id = objects.target_ids()[k];
    EXPECT_EQ(objects.target_index(id), static_cast<int>(k));
    EXPECT_EQ(objects.targets()[k].object, &objects[id].object);
    EXPECT_TRUE(objects.targets()[k].X_WO.isApprox(At(id, 0, 0)));
    const double half = 0.05 * (id + 1) + kMargin;
    EXPECT_NEAR(objects.target_boxes()[k].min().x(), id - half, 1e-12);
    EXPECT_NEAR(objects.target_boxes()[k].max().z(), half, 1e-12);
  }
  EXPECT_DOUBLE_EQ(objects.smallest_edge_m(), 0.1);
}

// Moving bodies and tools at random keeps the broad phase's pairs equal to
// the pairs of overlapping grown boxes, computed by brute force.
TEST(SceneObjectsTest, PairsMatchBoxesAfterMoves) {
  SceneObjects objects;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<ObjectKind> kinds;
  for (int i = 0; i < 12; ++i) {
    kinds.push_back(i % 3 == 0   ? ObjectKind::kFixed
                    : i % 3 == 1 ? ObjectKind::kFree
                                 : ObjectKind::kTool);
    AddCube(objects, 0.2, kinds.back(), At(u(rng), u(rng), u(rng)));
  }
  std::vector<Isometry3d> poses(12);
  for (int i = 0; i < 12; ++i) poses[i] = objects[i].X_WO;
  std::vector<std::pair<ObjectId, ObjectId>> pairs;
  for (int round = 0; round < 20; ++round) {
    for (ObjectId id = 0; id < 12; ++id) {
      if (kinds[id] == ObjectKind::kFixed) continue;
      poses[id] = At(u(rng), u(rng), u(rng));
      if (kinds[id] == ObjectKind::kFree) {
        objects.MoveBody(id, poses[id]);
        EXPECT_TRUE(objects.targets()[objects.target_index(id)].X_WO.isApprox(poses[id]));
      } else {
        objects.PoseTool(id, poses[id]);
      }
    }
    objects.FindCandidatePairs(pairs);
    std::vector<std::pair<ObjectId, ObjectId>> expected;
    for (ObjectId a = 0; a < 12; ++a) {
      for (ObjectId b = a + 1; b < 12; ++b) {
        if (objects.GrownBox(a, poses[a]).intersects(objects.GrownBox(b, poses[b]))) {
          expected.emplace_back(a, b);
        }
      }
    }
    EXPECT_EQ(pairs, expected) << "round " << round;
  }
}

}  // namespace
}  // namespace hs

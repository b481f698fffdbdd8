#include "common/sim/motion_bounds.h"

#include <gtest/gtest.h>

#include <random>

#include "common/model/procedural.h"

namespace hs {
namespace {

Isometry3d RandomPose(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  Isometry3d X = Isometry3d::Identity();
  X.linear() = Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized().toRotationMatrix();
  X.translation() = Vector3d(u(rng), u(rng), u(rng));
  return X;
}

// Oracle: every vertex, posed at sampled poses along the interpolation,
// lies in the swept box (and at the ends in the world boxes); rounding
// only (1e-12 m).
TEST(MotionBoundsTest, BoxesHoldEveryVertexAlongTheMotion) {
  std::mt19937 rng(7);
  const HapticObject torus = *HapticObject::Create("t", MakeTorus(0.1, 0.03, 12, 8));
  for (int trial = 0; trial < 50; ++trial) {
    const Isometry3d from = RandomPose(rng), to = RandomPose(rng);
    const AlignedBox3d swept = SweptBox(torus, from, to);
    const double travel = Travel(torus, from, to);
    for (int i = 0; i <= 20; ++i) {
      const Isometry3d X = InterpolatePose(from, to, i / 20.0);
      const AlignedBox3d world = WorldBox(torus, X);
      for (const Vector3d& p : torus.positions()) {
        const Vector3d q = X * p;
        EXPECT_LE(swept.exteriorDistance(q), 1e-12);
        EXPECT_LE(world.exteriorDistance(q), 1e-12);
        EXPECT_LE((q - from * p).norm(), travel + 1e-12);
      }
    }
  }
}

// The interpolation starts and ends at the given poses.
TEST(MotionBoundsTest, InterpolationEnds) {
  std::mt19937 rng(8);
  const Isometry3d from = RandomPose(rng), to = RandomPose(rng);
  EXPECT_TRUE(InterpolatePose(from, to, 0).isApprox(from, 1e-12));
  EXPECT_TRUE(InterpolatePose(from, to, 1).isApprox(to, 1e-12));
}

// Each sub-step travels strictly less than the limit, with the fewest
// sub-steps, up to the cap.
TEST(MotionBoundsTest, SubstepCount) {
  EXPECT_EQ(SubstepCount(0.004, 0.005, 256), 1);
  EXPECT_EQ(SubstepCount(0.005, 0.005, 256), 2);
  EXPECT_EQ(SubstepCount(0.202, 0.005, 256), 41);
  EXPECT_LT(0.202 / 41, 0.005);
  EXPECT_GE(0.202 / 40, 0.005);
  EXPECT_EQ(SubstepCount(100, 0.005, 256), 256);
  EXPECT_EQ(SubstepCount(1, 0, 256), 1);
}

}  // namespace
}  // namespace hs

#include "tests/common/contact/brute_force_depth.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "common/model/import.h"
#include "common/model/procedural.h"
#include "tests/common/contact/contact_test_bodies.h"
#include "tests/common/random_poses.h"
#include "tests/common/test_data_dir.h"

namespace hs::reference {
namespace {

using testing_bodies::Body;
using testing_bodies::MakeBody;
using testing_bodies::Translation;
using testing_poses::RandomDirection;
using testing_poses::RandomPose;

// A 1 m x 1 m x 0.2 m slab whose top face is the plane z = 0.
std::unique_ptr<Body> Slab() {
  return MakeBody(MakeBox(Vector3d(1, 1, 0.2)), Translation(0, 0, -0.1));
}

// A direction into the slab, at least 17 degrees off its surface.
Vector3d DownDirection(std::mt19937& rng) {
  Vector3d D = RandomDirection(rng);
  while (D.z() > -0.3) D = RandomDirection(rng);
  return D;
}

// A box turned at random and pressed into the slab's top leaves it when its
// lowest corner reaches z = 0: centre z minus the half sizes projected on
// z, over -D_z. The oracle gives that to long double rounding.
TEST(BruteForceDepthTest, BoxIntoSlabIsAnalytic) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  const Vector3d half(0.01, 0.02, 0.03);
  const auto slab = Slab();
  for (int i = 0; i < 20; ++i) {
    Isometry3d X = RandomPose(rng, 0.1);
    const double press = 0.001 + 0.004 * u(rng);
    const double z_min_offset = (X.linear().row(2).cwiseAbs().transpose().cwiseProduct(half)).sum();
    X.translation().z() = z_min_offset - press;
    const auto box = MakeBody(MakeBox(2 * half), X);
    const Vector3d D = DownDirection(rng);
    const BruteForceDepth ref = ComputeBruteForceDepth(box->posed(), slab->posed(), D, 1e-9);
    ASSERT_TRUE(ref.colliding);
    EXPECT_EQ(ref.pairs, 12 * 12);
    // The analytic value is itself rounded in double: a few ulps of 0.1 m.
    EXPECT_NEAR(static_cast<double>(ref.depth_m), press / -D.z(), 1e-15) << "pose " << i;
  }
}

// Apart by 1 mm, nothing collides and the depth is 0.
TEST(BruteForceDepthTest, ApartIsNotColliding) {
  const auto slab = Slab();
  const auto box = MakeBody(MakeBox(Vector3d(0.02, 0.02, 0.02)), Translation(0, 0, 0.011));
  const BruteForceDepth ref =
      ComputeBruteForceDepth(box->posed(), slab->posed(), -Vector3d::UnitZ(), 1e-9);
  EXPECT_FALSE(ref.colliding);
  EXPECT_EQ(ref.depth_m, 0);
}

// On a small non-convex pair (the imported kidney model, 128 faces, pressed
// by a coarse torus at random poses) the oracle and ComputeContact's exact
// method agree within the touching tolerance: the method's BVH search
// finds every pair that decides t*.
TEST(BruteForceDepthTest, AgreesWithSweepMethodOnNonConvexPair) {
  absl::StatusOr<ImportedModel> kidney = ImportModel(hs::TestDataDir() + "/kidney.obj");
  ASSERT_TRUE(kidney.ok()) << kidney.status();
  EXPECT_EQ(kidney->object.num_faces(), 128);
  const auto fixed = MakeBody(std::move(kidney->object));
  // Non-convex: some corner lies outside the plane of some face.
  const HapticObject& k = fixed->object;
  bool non_convex = false;
  for (const Face& f : k.faces()) {
    const Vector3d n = (k.position(f.vertices[1]) - k.position(f.vertices[0]))
                           .cross(k.position(f.vertices[2]) - k.position(f.vertices[0]));
    for (const Vector3d& p : k.positions()) {
      non_convex |= n.normalized().dot(p - k.position(f.vertices[0])) > 1e-3;
    }
  }
  EXPECT_TRUE(non_convex);
  std::mt19937 rng(2026);
  int colliding = 0;
  double deepest = 0;
  for (int i = 0; i < 200 && colliding < 40; ++i) {
    const auto torus = MakeBody(MakeTorus(0.02, 0.006, 12, 6), RandomPose(rng, 0.04));
    const Vector3d D = RandomDirection(rng);
    const absl::StatusOr<ContactSet> set = ComputeContact(
        torus->posed(), fixed->posed(), {.direction_W = D, .method = ContactMethod::kSweep3d});
    ASSERT_TRUE(set.ok()) << set.status();
    const BruteForceDepth ref = ComputeBruteForceDepth(torus->posed(), fixed->posed(), D, 1e-9);
    EXPECT_EQ(set->colliding, ref.colliding) << "pose " << i;
    if (!set->colliding || !ref.colliding) continue;
    ++colliding;
    deepest = std::max(deepest, set->depth_m);
    // Runs chain across gaps up to the tolerance, so the two may differ by
    // rounding near that bound: within one tolerance (~1e-10 m here).
    EXPECT_NEAR(set->depth_m, static_cast<double>(ref.depth_m), set->tolerance_m) << "pose " << i;
  }
  // Enough contacts to mean something, deep ones among them.
  EXPECT_GE(colliding, 40);
  EXPECT_GT(deepest, 0.01);
}

}  // namespace
}  // namespace hs::reference

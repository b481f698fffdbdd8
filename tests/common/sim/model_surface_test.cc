// A tool's surface: only convex tools get one; it holds every face the
// tool may meet from anywhere within its reach (brute force over every
// face of the organ), in the world frame with its material; and a tool's
// models share it until the proxy, the radius or an obstacle moves on.

#include "common/sim/model_surface.h"

#include <gtest/gtest.h>

#include <random>
#include <set>

#include "common/collision/collision_model.h"
#include "common/contact/closest_points.h"
#include "common/model/procedural.h"
#include "tests/common/random_poses.h"

namespace hs {
namespace {

// An object with its hierarchy.
struct Body {
  HapticObject object;
  CollisionModel model;
  explicit Body(HapticObject o) : object(std::move(o)), model(object, BvType::kObbRss, 1e-9) {}
  PosedObject Posed(const Isometry3d& X_WO) const { return {&object, &model, X_WO}; }
};

Isometry3d At(const Vector3d& p) {
  Isometry3d X = Isometry3d::Identity();
  X.translation() = p;
  return X;
}

TEST(ModelSurfaceTest, OnlyConvexToolsAreConvex) {
  EXPECT_TRUE(IsConvexTool(*HapticObject::Create("cube", MakeBox(Vector3d(0.02, 0.01, 0.03)))));
  EXPECT_FALSE(IsConvexTool(*HapticObject::Create("ring", MakeTorus(0.02, 0.005, 12, 6))));
  // A cube with a corner pushed in.
  MeshInput dented = MakeBox(Vector3d::Constant(0.02));
  dented.positions[0] *= 0.5;
  EXPECT_FALSE(IsConvexTool(*HapticObject::Create("dented", std::move(dented))));
}

// For random proxies near the organ's surface and radii: every face of the
// organ that comes within the tool's reach (its farthest vertex from its
// origin) plus the surface's radius of the centre is in the surface, each
// triangle is an organ face where the organ is (so no face twice), and
// each has its face's material.
TEST(ModelSurfaceTest, HoldsEveryFaceTheToolMayMeetWithinItsReach) {
  const Body torus(*HapticObject::Create("organ", MakeTorus(0.1, 0.04, 96, 48)));
  const Body cube(*HapticObject::Create("probe", MakeBox(Vector3d::Constant(0.02))));
  const Isometry3d X_WO = At(Vector3d(0, 0, 0.04));
  const std::vector<PosedObject> obstacles = {torus.Posed(X_WO)};
  const double reach = std::sqrt(3.0) * 0.01;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> angle(0, 2 * M_PI), radius(0.002, 0.02);
  int held_total = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const double a = angle(rng), b = angle(rng);
    const Vector3d on_tube =
        Vector3d((0.1 + 0.04 * std::cos(b)) * std::cos(a), (0.1 + 0.04 * std::cos(b)) * std::sin(a),
                 0.04 + 0.04 * std::sin(b));
    const Vector3d p = on_tube + 0.015 * testing_poses::RandomDirection(rng);
    const double r = radius(rng);
    SurfaceKeeper keeper;
    const std::shared_ptr<const ModelSurface> s =
        keeper.Update(cube.Posed(At(p)), p, r, obstacles, false);
    ASSERT_TRUE(s) << "trial " << trial;
    EXPECT_EQ(s->center_W, p);
    EXPECT_EQ(s->radius_m, kSurfaceReachFraction * r);
    EXPECT_EQ(s->tool_triangles.size(), 12u);
    std::set<std::array<double, 9>> held;
    for (size_t i = 0; i < s->triangles.size(); ++i) {
      const auto& t = s->triangles[i];
      std::array<double, 9> key;
      for (int k = 0; k < 3; ++k) {
        for (int c = 0; c < 3; ++c) key[3 * k + c] = s->vertices_W[t[k]][c];
      }
      EXPECT_TRUE(held.insert(key).second) << "a face twice, trial " << trial;
      EXPECT_EQ(s->materials[s->triangle_materials[i]].stiffness_n_per_m,
                torus.object.materials()[0].stiffness_n_per_m);
    }
    held_total += static_cast<int>(held.size());
    std::set<std::array<double, 9>> organ;
    for (const Face& f : torus.object.faces()) {
      std::array<Vector3d, 3> w;
      std::array<double, 9> key;
      for (int k = 0; k < 3; ++k) {
        w[k] = X_WO * torus.object.position(f.vertices[k]);
        for (int c = 0; c < 3; ++c) key[3 * k + c] = w[k][c];
      }
      organ.insert(key);
      const double distance = (ClosestPointOnTriangle(p, w[0], w[1], w[2]) - p).norm();
      if (distance <= reach + s->radius_m) {
        EXPECT_TRUE(held.count(key)) << "a face " << distance << " m away missed, trial " << trial;
      }
    }
    for (const auto& key : held) EXPECT_TRUE(organ.count(key)) << "not an organ face";
  }
  EXPECT_GT(held_total, 40 * 20);
}

// The same surface (the same object, its revision) while the proxy stays
// within kSurfaceMoveFraction of the radius of its centre, with the same
// radius and obstacles; a new revision past that, for another radius, a
// moved obstacle, or when asked; none for a tool that is not convex.
TEST(ModelSurfaceTest, ModelsShareASurfaceUntilTheProxyMovesOn) {
  const Body floor(*HapticObject::Create("floor", MakeBox(Vector3d(1, 1, 0.05))));
  const Body cube(*HapticObject::Create("probe", MakeBox(Vector3d::Constant(0.02))));
  std::vector<PosedObject> obstacles = {floor.Posed(At(Vector3d(0, 0, -0.025)))};
  const double r = 0.01;
  const Vector3d p(0, 0, 0.0100001);
  SurfaceKeeper keeper;
  const std::shared_ptr<const ModelSurface> first =
      keeper.Update(cube.Posed(At(p)), p, r, obstacles, false);
  ASSERT_TRUE(first);
  EXPECT_TRUE(keeper.changed());
  EXPECT_EQ(first->revision, 1u);
  EXPECT_GT(first->triangles.size(), 0u);
  const Vector3d near = p + Vector3d(0.9 * kSurfaceMoveFraction * r, 0, 0);
  EXPECT_EQ(keeper.Update(cube.Posed(At(near)), near, r, obstacles, false), first);
  EXPECT_FALSE(keeper.changed());
  const Vector3d far = p + Vector3d(1.1 * kSurfaceMoveFraction * r, 0, 0);
  const std::shared_ptr<const ModelSurface> moved =
      keeper.Update(cube.Posed(At(far)), far, r, obstacles, false);
  EXPECT_TRUE(keeper.changed());
  EXPECT_EQ(moved->revision, 2u);
  EXPECT_EQ(moved->center_W, far);
  EXPECT_EQ(keeper.Update(cube.Posed(At(far)), far, 2 * r, obstacles, false)->revision, 3u);
  obstacles[0].X_WO.translation().z() -= 1e-3;
  EXPECT_EQ(keeper.Update(cube.Posed(At(far)), far, 2 * r, obstacles, false)->revision, 4u);
  EXPECT_EQ(keeper.Update(cube.Posed(At(far)), far, 2 * r, obstacles, true)->revision, 5u);
  EXPECT_EQ(first->revision, 1u) << "a surface a frame holds is never written over";

  const Body ring(*HapticObject::Create("ring", MakeTorus(0.02, 0.005, 12, 6)));
  SurfaceKeeper ring_keeper;
  EXPECT_EQ(ring_keeper.Update(ring.Posed(At(p)), p, r, obstacles, false), nullptr);
  EXPECT_FALSE(ring_keeper.changed());
}

}  // namespace
}  // namespace hs

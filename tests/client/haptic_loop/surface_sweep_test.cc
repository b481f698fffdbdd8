// The sweep of a convex tool against a surface's triangles: against CGAL's
// exact intersection predicate (where it first touches, and that the
// normal it reports separates the two), and against the server's own
// first touch (common/contact, FCL underneath) on the demo organ.

#include "client/haptic_loop/surface_sweep.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/intersections.h>
#include <gtest/gtest.h>

#include <random>

#include "common/collision/collision_model.h"
#include "common/contact/contact_query.h"
#include "common/model/procedural.h"
#include "tests/common/random_poses.h"

namespace hs {
namespace {

using testing_poses::RandomDirection;
using testing_poses::RandomPose;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

constexpr double kHalf = 0.01;  // the tool: a 2 cm cube about its origin

// A surface of `triangles` (world frame) with the 2 cm cube as its tool.
ModelSurface CubeSurface(const std::vector<std::array<Vector3d, 3>>& triangles) {
  const HapticObject cube = *HapticObject::Create("cube", MakeBox(Vector3d::Constant(2 * kHalf)));
  ModelSurface s{.revision = 1, .radius_m = 1};
  s.tool_vertices_T.assign(cube.positions().begin(), cube.positions().end());
  for (const Face& f : cube.faces()) s.tool_triangles.push_back(f.vertices);
  s.materials.push_back({.stiffness_n_per_m = 400});
  for (const auto& t : triangles) {
    const int32_t first = static_cast<int32_t>(s.vertices_W.size());
    s.vertices_W.insert(s.vertices_W.end(), t.begin(), t.end());
    s.triangles.push_back({first, first + 1, first + 2});
    s.triangle_materials.push_back(0);
  }
  return s;
}

// Whether the cube turned by R with its origin at p meets triangle t,
// exactly (the triangle taken into the cube's frame first).
bool Meets(const Matrix3d& R, const Vector3d& p, const std::array<Vector3d, 3>& t) {
  auto point = [&](const Vector3d& x) {
    const Vector3d y = R.transpose() * (x - p);
    return Kernel::Point_3(y.x(), y.y(), y.z());
  };
  const Kernel::Iso_cuboid_3 cube(Kernel::Point_3(-kHalf, -kHalf, -kHalf),
                                  Kernel::Point_3(kHalf, kHalf, kHalf));
  return CGAL::do_intersect(Kernel::Triangle_3(point(t[0]), point(t[1]), point(t[2])), cube);
}

// A triangle of sides about 1-3 cm near the origin.
std::array<Vector3d, 3> RandomTriangle(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-0.02, 0.02);
  const Vector3d c(u(rng), u(rng), u(rng));
  return {c + Vector3d(u(rng), u(rng), u(rng)), c + Vector3d(u(rng), u(rng), u(rng)),
          c + Vector3d(u(rng), u(rng), u(rng))};
}

// For random turns of the cube, triangles and moves: where the sweep says
// the cube first touches a triangle, the cube there pushed 1e-9 m back
// along the normal does not meet it and pushed 1e-9 m in does (so the time
// and the normal are the contact's), and no earlier point of the move
// meets it; where it says none, no point of the move does.
TEST(SurfaceSweepTest, FirstTouchIsExactAndItsNormalSeparates) {
  std::mt19937 rng(7);
  constexpr double kPush = 1e-9;
  int touches = 0, misses = 0;
  for (int trial = 0; trial < 600; ++trial) {
    const std::array<Vector3d, 3> t = RandomTriangle(rng);
    SurfaceSweep sweep;
    sweep.Set(CubeSurface({t}));
    const Matrix3d R = RandomPose(rng, 0).linear();
    sweep.Orient(R);
    // From outside, 3-6 cm away.
    const Vector3d start =
        t[0] + (0.03 + 0.03 * std::uniform_real_distribution<double>()(rng)) * RandomDirection(rng);
    if (Meets(R, start, t)) continue;
    // Toward the triangle and past it a little, or (one in three) anywhere.
    const Vector3d v = trial % 3 == 0
                           ? Vector3d(0.06 * RandomDirection(rng))
                           : Vector3d((t[1] + 0.01 * RandomDirection(rng) - start) * 1.2);
    const SurfaceSweep::Touch touch = sweep.First(start, v);
    const double end = touch.triangle < 0 ? 1.0 : touch.t;
    for (int k = 0; k < 200; ++k) {
      const double s = end * k / 200.0;
      ASSERT_FALSE(Meets(R, start + s * v, t) && s < end - 1e-9)
          << "trial " << trial << ": meets at " << s << " before " << end;
    }
    if (touch.triangle < 0) {
      ASSERT_FALSE(Meets(R, start + v, t)) << "trial " << trial;
      ++misses;
      continue;
    }
    ++touches;
    ASSERT_NEAR(touch.normal_W.norm(), 1, 1e-12);
    EXPECT_LT(touch.normal_W.dot(v), 0) << "trial " << trial << ": the move goes into it";
    const Vector3d at = start + touch.t * v;
    EXPECT_FALSE(Meets(R, at + kPush * touch.normal_W, t)) << "trial " << trial;
    EXPECT_TRUE(Meets(R, at - kPush * touch.normal_W, t)) << "trial " << trial;
  }
  EXPECT_GT(touches, 100);
  EXPECT_GT(misses, 50);
}

// A cube resting on a floor slightly sunk in it (as rounding leaves it) is
// met at once when it moves down, and not when it lifts off or slides.
TEST(SurfaceSweepTest, AToolInAFaceMayLeaveItButNotGoDeeper) {
  SurfaceSweep sweep;
  sweep.Set(CubeSurface({{Vector3d(-1, -1, 0), Vector3d(1, -1, 0), Vector3d(0, 1, 0)}}));
  const Vector3d p(0, 0, kHalf - 1e-12);
  const SurfaceSweep::Touch down = sweep.First(p, Vector3d(0.001, 0, -0.001));
  EXPECT_EQ(down.triangle, 0);
  EXPECT_EQ(down.t, 0);
  EXPECT_TRUE(down.normal_W.isApprox(Vector3d::UnitZ()));
  EXPECT_EQ(sweep.First(p, Vector3d(0, 0, 0.001)).triangle, -1);
  EXPECT_TRUE(sweep.Overlaps(p, 0));
  EXPECT_FALSE(sweep.Overlaps(p, 1e-9));
  // Resting 1e-9 m above, a slide along it meets nothing.
  EXPECT_EQ(sweep.First(Vector3d(0, 0, kHalf + 1e-9), Vector3d(0.01, 0.003, 0)).triangle, -1);
  EXPECT_LT((sweep.TouchPoint(p, Vector3d::UnitZ()) - Vector3d(0, 0, -1e-12)).norm(), 1e-15);
}

// On the demo organ (the torus of probe_on_torus), the sweep of the probe
// against the faces near it gives the server's first touch (FindFirstTouch,
// FCL's continuous collision underneath): the same time within 1e-6 of the
// move, and the same normal where the touch is a single feature pair.
TEST(SurfaceSweepTest, AgreesWithTheServersFirstTouchOnTheOrgan) {
  const HapticObject torus = *HapticObject::Create("organ", MakeTorus(0.1, 0.04, 96, 48));
  const CollisionModel torus_model(torus, BvType::kObbRss, 1e-9);
  const HapticObject cube = *HapticObject::Create("probe", MakeBox(Vector3d::Constant(2 * kHalf)));
  const CollisionModel cube_model(cube, BvType::kObbRss, 1e-9);
  std::vector<std::array<Vector3d, 3>> faces;
  for (const Face& f : torus.faces()) {
    faces.push_back({torus.position(f.vertices[0]), torus.position(f.vertices[1]),
                     torus.position(f.vertices[2])});
  }
  SurfaceSweep sweep;
  sweep.Set(CubeSurface(faces));
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> angle(0, 2 * M_PI);
  int compared = 0, same_normal = 0;
  for (int trial = 0; trial < 300; ++trial) {
    // Above the tube's top, moving down and sideways.
    const double a = angle(rng);
    const Vector3d top(0.1 * std::cos(a), 0.1 * std::sin(a), 0.04);
    const Vector3d start = top + Vector3d(0, 0, kHalf + 0.005) + 0.01 * RandomDirection(rng);
    const Matrix3d R =
        trial % 2 == 0 ? Matrix3d(Matrix3d::Identity()) : Matrix3d(RandomPose(rng, 0).linear());
    sweep.Orient(R);
    if (sweep.Overlaps(start, 0)) continue;
    const Vector3d v = Vector3d(0, 0, -0.03) + 0.02 * RandomDirection(rng);
    Isometry3d X_end = Isometry3d::Identity();
    X_end.linear() = R;
    X_end.translation() = start + v;
    const auto server = FindFirstTouch({&cube, &cube_model, X_end},
                                       {&torus, &torus_model, Isometry3d::Identity()}, v, 1e-9);
    ASSERT_TRUE(server.ok()) << server.status();
    const SurfaceSweep::Touch touch = sweep.First(start, v);
    ASSERT_EQ(server->has_value(), touch.triangle >= 0) << "trial " << trial;
    if (!server->has_value()) continue;
    ++compared;
    EXPECT_NEAR(touch.t, (*server)->time, 1e-6) << "trial " << trial;
    if (touch.normal_W.isApprox((*server)->normal_W, 1e-6)) ++same_normal;
  }
  EXPECT_GT(compared, 150);
  // Where they differ the touch is at a vertex or an edge shared by
  // several faces, whose normals both are.
  EXPECT_GT(same_normal, compared * 9 / 10);
}

}  // namespace
}  // namespace hs

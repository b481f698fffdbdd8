#include "common/sim/local_model_builder.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <optional>
#include <random>
#include <vector>

#include "common/collision/triangle_pairs.h"
#include "common/model/procedural.h"
#include "tests/common/contact/contact_test_bodies.h"
#include "tests/common/random_poses.h"
#include "tests/common/sim/at_pose.h"

namespace hs {
namespace {

using testing_bodies::Body;
using testing_bodies::MakeBody;

constexpr double kTool = 0.02;  // the tool: a cube of this side
constexpr double kRadius = 0.01;

// A 1 m x 1 m x 0.1 m floor with its top at z = 0, its material `material`.
std::unique_ptr<Body> Floor(const Material& material = {}) {
  MeshInput mesh = MakeBox(Vector3d(1, 1, 0.1));
  mesh.materials[0] = material;
  return MakeBody(std::move(mesh), At(0, 0, -0.05));
}

std::unique_ptr<Body> Tool() { return MakeBody(MakeBox(Vector3d::Constant(kTool))); }

ProxyState ProxyAt(const Isometry3d& X_WP) {
  ProxyState proxy;
  proxy.X_WP = X_WP;
  return proxy;
}

LocalModel Build(const Body& tool, const ProxyState& proxy,
                 const std::vector<const Body*>& obstacles, const std::vector<ObjectId>& ids,
                 const LocalModelOptions& options = {.radius_m = kRadius}) {
  std::vector<PosedObject> posed;
  for (const Body* body : obstacles) posed.push_back(body->posed());
  LocalModel model;
  BuildLocalModel(tool.posed(), proxy, proxy.X_WP.translation() + Vector3d(0, 0, -0.001), posed,
                  ids, options, model);
  return model;
}

// A tool `gap` above the floor: one plane (its four bottom corners over the
// floor's top give the same plane), the floor's top, with the floor's id
// and material; the model carries the proxy, the device and the options.
TEST(LocalModelBuilderTest, FloorUnderTheToolGivesItsPlane) {
  const Material material{.name = "felt",
                          .stiffness_n_per_m = 700,
                          .damping_ns_per_m = 2,
                          .static_friction = 0.5,
                          .dynamic_friction = 0.4};
  const auto floor = Floor(material);
  auto tool = Tool();
  tool->X_WO = At(5, 5, 5);  // ignored: the proxy places the tool
  const double gap = 0.004;
  const ProxyState proxy = ProxyAt(At(0.1, 0.05, kTool / 2 + gap));
  const LocalModelOptions options{
      .radius_m = kRadius, .max_planes = 4, .force_clamp_n = 7, .friction = true};
  const LocalModel model = Build(*tool, proxy, {floor.get()}, {42}, options);
  EXPECT_TRUE(model.X_WP.isApprox(proxy.X_WP));
  EXPECT_EQ(model.p_WD, Vector3d(0.1, 0.05, kTool / 2 + gap - 0.001));
  EXPECT_EQ(model.validity_radius_m, kRadius);
  EXPECT_EQ(model.force_clamp_n, 7);
  EXPECT_TRUE(model.friction);
  ASSERT_EQ(model.planes.size(), 1u);
  const ConstraintPlane& plane = model.planes[0];
  EXPECT_EQ(plane.object, 42);
  EXPECT_TRUE(plane.normal_W.isApprox(Vector3d::UnitZ(), 1e-12));
  EXPECT_NEAR(plane.gap_m, gap, 1e-12);
  EXPECT_NEAR(plane.point_W.z(), 0, 1e-12);
  // The tool's point is a bottom corner, straight above the plane's point.
  EXPECT_NEAR(std::abs(plane.tool_point_W.x() - 0.1), kTool / 2, 1e-12);
  EXPECT_NEAR(std::abs(plane.tool_point_W.y() - 0.05), kTool / 2, 1e-12);
  EXPECT_TRUE((plane.tool_point_W - plane.point_W).isApprox(gap * Vector3d::UnitZ(), 1e-9));
  EXPECT_EQ(plane.stiffness_n_per_m, 700);
  EXPECT_EQ(plane.damping_ns_per_m, 2);
  EXPECT_EQ(plane.static_friction, 0.5);
  EXPECT_EQ(plane.dynamic_friction, 0.4);
}

// The floor counts while the tool is within the radius of it, not beyond.
TEST(LocalModelBuilderTest, OnlyFacesWithinTheRadiusGivePlanes) {
  const auto floor = Floor();
  const auto tool = Tool();
  EXPECT_EQ(
      Build(*tool, ProxyAt(At(0, 0, kTool / 2 + 0.99 * kRadius)), {floor.get()}, {0}).planes.size(),
      1u);
  EXPECT_TRUE(Build(*tool, ProxyAt(At(0, 0, kTool / 2 + 1.01 * kRadius)), {floor.get()}, {0})
                  .planes.empty());
}

// A touching proxy's model holds its contact point as the lever; a free
// one's the proxy's origin.
TEST(LocalModelBuilderTest, TouchPointIsTheContactOrTheProxyOrigin) {
  const auto floor = Floor();
  const auto tool = Tool();
  ProxyState proxy = ProxyAt(At(0.1, 0.05, kTool / 2));
  LocalModel model = Build(*tool, proxy, {floor.get()}, {0});
  EXPECT_FALSE(model.touching);
  EXPECT_EQ(model.touch_point_W, proxy.X_WP.translation());
  proxy.touching = true;
  proxy.p_WC = Vector3d(0.1, 0.05, 0);
  model = Build(*tool, proxy, {floor.get()}, {0});
  EXPECT_TRUE(model.touching);
  EXPECT_EQ(model.touch_point_W, proxy.p_WC);
}

// In an inside corner (a floor and a wall at x = 0.2) the tool gets both
// planes, nearest first; a cap of one keeps the nearer.
TEST(LocalModelBuilderTest, PlanesAreNearestFirstAndCapped) {
  const auto floor = Floor();
  const auto wall = MakeBody(MakeBox(Vector3d(0.1, 1, 1)), At(0.25, 0, 0.5));
  const auto tool = Tool();
  const ProxyState proxy = ProxyAt(At(0.2 - kTool / 2 - 0.002, 0, kTool / 2 + 0.005));
  const LocalModel model = Build(*tool, proxy, {floor.get(), wall.get()}, {1, 2});
  ASSERT_EQ(model.planes.size(), 2u);
  EXPECT_EQ(model.planes[0].object, 2);
  EXPECT_TRUE(model.planes[0].normal_W.isApprox(-Vector3d::UnitX(), 1e-12));
  EXPECT_NEAR(model.planes[0].gap_m, 0.002, 1e-12);
  EXPECT_EQ(model.planes[1].object, 1);
  EXPECT_TRUE(model.planes[1].normal_W.isApprox(Vector3d::UnitZ(), 1e-12));
  EXPECT_NEAR(model.planes[1].gap_m, 0.005, 1e-12);
  const LocalModel capped = Build(*tool, proxy, {floor.get(), wall.get()}, {1, 2},
                                  {.radius_m = kRadius, .max_planes = 1});
  ASSERT_EQ(capped.planes.size(), 1u);
  EXPECT_EQ(capped.planes[0].object, 2);
}

// The model does not depend on the order the obstacles come in.
TEST(LocalModelBuilderTest, ObstacleOrderDoesNotMatter) {
  const auto floor = Floor();
  const auto sphere = MakeBody(MakeIcosphere(0.05, 2), At(0.06, 0, 0.05));
  const auto tool = Tool();
  std::mt19937 rng(8);
  for (int k = 0; k < 20; ++k) {
    Isometry3d X_WP = testing_poses::RandomPose(rng, 0.02);
    X_WP.translation() += Vector3d(0, 0, 0.025);
    const LocalModel a = Build(*tool, ProxyAt(X_WP), {floor.get(), sphere.get()}, {1, 2});
    const LocalModel b = Build(*tool, ProxyAt(X_WP), {sphere.get(), floor.get()}, {2, 1});
    ASSERT_EQ(a.planes.size(), b.planes.size()) << k;
    for (size_t i = 0; i < a.planes.size(); ++i) {
      EXPECT_EQ(a.planes[i].object, b.planes[i].object) << k;
      EXPECT_EQ(a.planes[i].normal_W, b.planes[i].normal_W) << k;
      EXPECT_EQ(a.planes[i].gap_m, b.planes[i].gap_m) << k;
      EXPECT_EQ(a.planes[i].tool_point_W, b.planes[i].tool_point_W) << k;
    }
  }
}

// The model's promise, against the geometry itself: a translation of the
// tool within the radius that keeps it in front of every plane never makes
// it meet the obstacle. A turned cube over the inside of the floor's top, at
// random turns, places and gaps; translations drawn at random in the ball of
// the radius, kept when they satisfy every plane with a small slack. Over
// the floor's inside the nearest features are the floor's face and the
// tool's corners or edges. (Where they are not, beside a faceted ball's
// vertex or edge, the builder may hold no plane at all though the ball is
// within the radius: the planes are taken only where a feature's foot lies
// on the other feature.)
TEST(LocalModelBuilderTest, TranslationsThePlanesAllowMeetNothing) {
  const auto floor = Floor();
  const auto tool = Tool();
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> unit(0, 1);
  int allowed = 0;
  for (int k = 0; k < 60; ++k) {
    // A turned tool lowered until it meets the floor, then raised a
    // random gap.
    Isometry3d X_WP = testing_poses::RandomPose(rng, 0.3);
    double height = 0.05;
    auto at = [&](double z) {
      Isometry3d X = X_WP;
      X.translation().z() = z;
      return X;
    };
    while (!AnyTrianglesMeet(tool->model, at(height), std::nullopt, floor->model, floor->X_WO, 0)) {
      height -= 1e-4;
    }
    X_WP = at(height + 1e-4 + 0.8 * kRadius * unit(rng));
    const LocalModel model =
        Build(*tool, ProxyAt(X_WP), {floor.get()}, {0}, {.radius_m = kRadius, .max_planes = 64});
    ASSERT_FALSE(model.planes.empty()) << k;
    for (int j = 0; j < 200; ++j) {
      const Vector3d step =
          0.9 * kRadius * std::cbrt(unit(rng)) * testing_poses::RandomDirection(rng);
      bool in_front = true;
      for (const ConstraintPlane& plane : model.planes) {
        in_front &= plane.gap_m + plane.normal_W.dot(step) > 1e-5;
      }
      if (!in_front) continue;
      ++allowed;
      Isometry3d moved = X_WP;
      moved.translation() += step;
      ASSERT_FALSE(AnyTrianglesMeet(tool->model, moved, std::nullopt, floor->model, floor->X_WO, 0))
          << "case " << k << ", step " << step.transpose();
    }
  }
  EXPECT_GT(allowed, 1000);  // the draws reached both sides of the planes
}

}  // namespace
}  // namespace hs

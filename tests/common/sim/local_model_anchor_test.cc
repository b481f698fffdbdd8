#include "common/sim/local_model_anchor.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <random>
#include <vector>

#include "common/model/procedural.h"
#include "common/sim/local_model_builder.h"
#include "tests/common/contact/contact_test_bodies.h"
#include "tests/common/sim/at_pose.h"

namespace hs {
namespace {

using testing_bodies::Body;
using testing_bodies::MakeBody;

constexpr double kRadius = 0.01;
constexpr double kBehind = 1e-9;

ConstraintPlane Plane(const Vector3d& point, const Vector3d& normal, double gap,
                      const Vector3d& tool_point) {
  ConstraintPlane plane;
  plane.point_W = point;
  plane.normal_W = normal.normalized();
  plane.gap_m = gap;
  plane.tool_point_W = tool_point;
  return plane;
}

// A model at the origin: a floor touched (z = 0, gap 0) and a wall 4 mm
// away along +x (its normal -x), a 1 cm radius.
LocalModel FloorAndWall() {
  LocalModel model;
  model.revision = 7;
  model.validity_radius_m = kRadius;
  model.force_clamp_n = 10;
  model.touching = true;
  model.planes = {Plane(Vector3d(0, 0, -0.01), Vector3d::UnitZ(), 0, Vector3d(0, 0, -0.01)),
                  Plane(Vector3d(0.014, 0, 0), -Vector3d::UnitX(), 0.004, Vector3d(0.01, 0, 0))};
  return model;
}

ProxyState TouchingAt(const Vector3d& p) {
  ProxyState proxy;
  proxy.X_WP = At(p.x(), p.y(), p.z());
  proxy.touching = true;
  proxy.p_WC = p + Vector3d(0, 0, -0.01);
  return proxy;
}

// How far a point `p` of the free space lies in front of `plane` of
// `model` (the haptic loop's reading: gap plus the move from the proxy).
double Ahead(const LocalModel& model, const ConstraintPlane& plane, const Vector3d& p) {
  return plane.gap_m + plane.normal_W.dot(p - model.X_WP.translation());
}

// Slid 1 mm toward the wall: the wall's gap is 1 mm less (computed by
// hand), the floor's unchanged; the radius is 1 mm less; the tool points
// move with the tool; the anchor, device and touch are the new ones; the
// revision is the caller's.
TEST(LocalModelAnchorTest, SlideMovesTheGapsByHand) {
  const LocalModel built = FloorAndWall();
  LocalModel out;
  out.revision = 3;
  const Vector3d device(0.001, 0, -0.002);
  ASSERT_TRUE(AnchorLocalModel(built, TouchingAt(Vector3d(0.001, 0, 0)), device, kBehind, out));
  EXPECT_EQ(out.revision, 3u);
  EXPECT_DOUBLE_EQ(out.validity_radius_m, 0.009);
  EXPECT_EQ(out.X_WP.translation(), Vector3d(0.001, 0, 0));
  EXPECT_EQ(out.p_WD, device);
  EXPECT_TRUE(out.touching);
  EXPECT_EQ(out.touch_point_W, Vector3d(0.001, 0, -0.01));
  ASSERT_EQ(out.planes.size(), 2u);
  EXPECT_EQ(out.planes[0].gap_m, 0);
  EXPECT_DOUBLE_EQ(out.planes[1].gap_m, 0.003);
  EXPECT_EQ(out.planes[1].tool_point_W, Vector3d(0.011, 0, 0));
  EXPECT_DOUBLE_EQ(out.planes[1].point_W.x(), 0.014);  // on the plane, beside the tool point
  EXPECT_EQ(out.force_clamp_n, built.force_clamp_n);
}

// The anchored model is the same half-spaces: at random points, each
// plane reads the same distance ahead from either anchor.
TEST(LocalModelAnchorTest, PlanesStayWhereTheyWere) {
  const LocalModel built = FloorAndWall();
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.002, 0.002);
  for (int trial = 0; trial < 100; ++trial) {
    const Vector3d slide(u(rng), u(rng), 0);
    LocalModel out;
    ASSERT_TRUE(AnchorLocalModel(built, TouchingAt(slide), slide, kBehind, out));
    ASSERT_EQ(out.planes.size(), built.planes.size());
    for (size_t i = 0; i < out.planes.size(); ++i) {
      const Vector3d p(u(rng), u(rng), u(rng));
      EXPECT_NEAR(Ahead(out, out.planes[i], p), Ahead(built, built.planes[i], p), 1e-17) << trial;
      // The torque's lever from the proxy to the tool point is the tool's own.
      EXPECT_TRUE((out.planes[i].tool_point_W - out.X_WP.translation())
                      .isApprox(built.planes[i].tool_point_W, 1e-15));
    }
  }
}

// A slide that brings a farther plane nearer than a nearer one reorders
// them nearest first; a plane left beyond the smaller radius is dropped.
TEST(LocalModelAnchorTest, PlanesStayNearestFirstWithinTheRadius) {
  LocalModel built = FloorAndWall();
  built.planes[0].gap_m = 0.002;  // the floor 2 mm below the tool
  built.planes.push_back(
      Plane(Vector3d(-0.019, 0, 0), Vector3d::UnitX(), 0.0095, Vector3d(-0.01, 0, 0)));
  std::sort(built.planes.begin(), built.planes.end(), NearerPlane);
  LocalModel out;
  // 3 mm toward +x: the wall 1 mm ahead, the floor 2 mm, the back wall at
  // 12.5 mm beyond the 7 mm left of the radius.
  ASSERT_TRUE(
      AnchorLocalModel(built, TouchingAt(Vector3d(0.003, 0, 0)), Vector3d::Zero(), kBehind, out));
  ASSERT_EQ(out.planes.size(), 2u);
  EXPECT_EQ(out.planes[0].normal_W, -Vector3d::UnitX());
  EXPECT_NEAR(out.planes[0].gap_m, 0.001, 1e-15);
  EXPECT_EQ(out.planes[1].normal_W, Vector3d::UnitZ());
}

// A turn, a slide as far as the radius, and a slide past a plane (the tool
// behind it: the faces near it are others) each ask for a new model, and
// leave `out` as it was; a move within rounding behind a touched plane
// does not.
TEST(LocalModelAnchorTest, RefusesTurnsFarSlidesAndCrossedPlanes) {
  const LocalModel built = FloorAndWall();
  LocalModel out;
  out.revision = 9;
  ProxyState turned = TouchingAt(Vector3d::Zero());
  turned.X_WP.linear() = Eigen::AngleAxisd(1e-9, Vector3d::UnitZ()).toRotationMatrix();
  EXPECT_FALSE(AnchorLocalModel(built, turned, Vector3d::Zero(), kBehind, out));
  EXPECT_FALSE(
      AnchorLocalModel(built, TouchingAt(Vector3d(0, 0.01, 0)), Vector3d::Zero(), kBehind, out));
  EXPECT_FALSE(
      AnchorLocalModel(built, TouchingAt(Vector3d(0, 0, -1e-6)), Vector3d::Zero(), kBehind, out));
  EXPECT_FALSE(AnchorLocalModel(built, TouchingAt(Vector3d(0.005, 0, 0)), Vector3d::Zero(), kBehind,
                                out));  // past the wall
  EXPECT_EQ(out.revision, 9u);
  EXPECT_TRUE(out.planes.empty());
  ASSERT_TRUE(
      AnchorLocalModel(built, TouchingAt(Vector3d(0, 0, -1e-10)), Vector3d::Zero(), kBehind, out));
  EXPECT_EQ(out.planes[0].gap_m, 0);
}

// The oracle: a model built afresh. A cube tool resting on a floor and
// sliding along it 2 mm, its corners kept off the floor's diagonal edge: the planes within the
// anchored radius are the ones a model built at the new proxy with that radius has, plane for plane
// (normals, gaps and levers within rounding).
TEST(LocalModelAnchorTest, OnAFloorItIsTheModelBuiltThere) {
  std::unique_ptr<Body> floor = MakeBody(MakeBox(Vector3d(1, 1, 0.1)), At(0, 0, -0.05));
  std::unique_ptr<Body> tool = MakeBody(MakeBox(Vector3d::Constant(0.02)));
  const std::vector<PosedObject> obstacles{floor->posed()};
  const std::vector<ObjectId> ids{0};
  auto build = [&](const ProxyState& proxy, double radius_m) {
    LocalModel model;
    BuildLocalModel(tool->posed(), proxy, proxy.X_WP.translation(), obstacles, ids,
                    {.radius_m = radius_m}, model);
    return model;
  };
  const ProxyState start = TouchingAt(Vector3d(0.004, -0.002, 0.01));
  const LocalModel built = build(start, kRadius);
  ASSERT_FALSE(built.planes.empty());
  const ProxyState slid = TouchingAt(Vector3d(0.0052, -0.0036, 0.01));
  LocalModel anchored;
  ASSERT_TRUE(AnchorLocalModel(built, slid, slid.X_WP.translation(),
                               PlaneTouchTolerance(tool->object), anchored));
  const LocalModel fresh = build(slid, anchored.validity_radius_m);
  ASSERT_EQ(anchored.planes.size(), fresh.planes.size());
  for (size_t i = 0; i < fresh.planes.size(); ++i) {
    EXPECT_TRUE(anchored.planes[i].normal_W.isApprox(fresh.planes[i].normal_W, 1e-12)) << i;
    EXPECT_NEAR(anchored.planes[i].gap_m, fresh.planes[i].gap_m, 1e-12) << i;
    EXPECT_NEAR(anchored.planes[i].normal_W.dot(anchored.planes[i].tool_point_W),
                fresh.planes[i].normal_W.dot(fresh.planes[i].tool_point_W), 1e-12)
        << i;
  }
}

}  // namespace
}  // namespace hs

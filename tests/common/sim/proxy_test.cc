#include "common/sim/proxy.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include "common/model/procedural.h"
#include "tests/common/sim/at_pose.h"

namespace hs {
namespace {

// An object with its hierarchy, posed.
struct Body {
  HapticObject object;
  CollisionModel model;
  Isometry3d X_WO;
  PosedObject Posed() const { return {&object, &model, X_WO}; }
};

std::unique_ptr<Body> MakeBody(const Vector3d& size, const Isometry3d& X_WO) {
  HapticObject object = *HapticObject::Create("box", MakeBox(size));
  CollisionModel model(object, BvType::kObbRss, 1e-6 * object.bounding_box().diagonal().norm());
  return std::make_unique<Body>(Body{std::move(object), std::move(model), X_WO});
}

// A 2 cm cube tool (its bottom 1 cm under its origin) over a floor whose
// top is z = 0 (`thickness` thick). Default material: static friction
// 0.3, dynamic 0.2. The proxy stops 1e-6 of the tool's diagonal (3.5e-8 m)
// off a surface; positions are checked to 1e-7 m.
struct Rig {
  explicit Rig(double thickness = 0.1)
      : floor(MakeBody(Vector3d(1, 1, thickness), At(0, 0, -thickness / 2))),
        tool(MakeBody(Vector3d::Constant(0.02), Isometry3d::Identity())) {
    obstacles.push_back(floor->Posed());
  }
  absl::StatusOr<ProxyState> Move(const Isometry3d& from, const Isometry3d& device,
                                  bool friction = false) const {
    return MoveProxy(tool->Posed(), from, device, obstacles,
                     {.relative_tolerance = 1e-9, .friction = friction});
  }
  std::unique_ptr<Body> floor, tool;
  std::vector<PosedObject> obstacles;
};

constexpr double kAt = 1e-7;
constexpr double kResting = 0.01;  // the tool's origin height on the floor

// Nothing in the way: the proxy is the device pose, orientation included.
TEST(ProxyTest, FreeSpaceFollowsTheDevice) {
  const Rig rig;
  Isometry3d device = At(0.1, -0.2, 0.3);
  device.linear() = Eigen::AngleAxisd(0.4, Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const ProxyState state = *rig.Move(At(0, 0, 0.05), device);
  EXPECT_FALSE(state.touching);
  EXPECT_TRUE(state.X_WP.isApprox(device, 1e-15));
}

// Straight down 5.5 cm to 5 mm under the floor's top: the proxy stops
// where the tool's bottom meets the top, z = 0.01, touching face up, the
// touching point on the plane z = 0.
TEST(ProxyTest, StopsOnTheSurface) {
  const Rig rig;
  const ProxyState state = *rig.Move(At(0, 0, 0.05), At(0, 0, -0.005));
  ASSERT_TRUE(state.touching);
  EXPECT_NEAR(state.X_WP.translation().z(), kResting, kAt);
  EXPECT_NEAR(state.X_WP.translation().x(), 0, 1e-12);
  EXPECT_EQ(state.obstacle, 0);
  EXPECT_TRUE(state.normal_W.isApprox(Vector3d::UnitZ(), 1e-9));
  EXPECT_NEAR(state.p_WC.z(), 0, kAt);
  // The touched face lies in the floor's top (z = 0 in the world).
  for (const VertexId v : rig.floor->object.face(state.face).vertices) {
    EXPECT_NEAR((rig.floor->X_WO * rig.floor->object.position(v)).z(), 0, 1e-12);
  }
}

// Without friction, a device 3 mm in and off to the side: the proxy
// slides on the surface to right above the device.
TEST(ProxyTest, SlidesToAboveTheDeviceWithoutFriction) {
  const Rig rig;
  const ProxyState state = *rig.Move(At(0, 0, kResting), At(0.1, 0.05, -0.003));
  ASSERT_TRUE(state.touching);
  EXPECT_NEAR(state.X_WP.translation().x(), 0.1, kAt);
  EXPECT_NEAR(state.X_WP.translation().y(), 0.05, kAt);
  EXPECT_NEAR(state.X_WP.translation().z(), kResting, kAt);
}

// With friction and the device 1 cm in (into = 1 cm): 2 mm to the side is
// inside the static cone (0.3 x 1 cm = 3 mm), so the proxy sticks; 5 mm is
// outside, and the proxy slides but lags by the dynamic friction's share,
// 0.2 x 1 cm: it moves 5 - 2 = 3 mm.
TEST(ProxyTest, FrictionSticksInsideTheConeAndLagsOutside) {
  const Rig rig;
  const double depth = kResting - 0.01;
  const ProxyState stuck = *rig.Move(At(0, 0, kResting), At(0.002, 0, depth), /*friction=*/true);
  ASSERT_TRUE(stuck.touching);
  EXPECT_NEAR(stuck.X_WP.translation().x(), 0, kAt);
  const ProxyState lagging = *rig.Move(At(0, 0, kResting), At(0.005, 0, depth), /*friction=*/true);
  ASSERT_TRUE(lagging.touching);
  EXPECT_NEAR(lagging.X_WP.translation().x(), 0.003, kAt);
  EXPECT_NEAR(lagging.X_WP.translation().z(), kResting, kAt);
}

// A 1 mm plate and a device that jumps 10 cm through it in one step: the
// proxy stays on top.
TEST(ProxyTest, NoPopThroughAThinPlate) {
  const Rig rig(0.001);
  const ProxyState state = *rig.Move(At(0, 0, 0.05), At(0, 0, -0.05));
  ASSERT_TRUE(state.touching);
  EXPECT_NEAR(state.X_WP.translation().z(), kResting, kAt);
}

// A device pose that is not finite is refused, as ComputeContact refuses it.
TEST(ProxyTest, NonFiniteDeviceIsRefused) {
  const Rig rig;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(rig.Move(At(0, 0, 0.05), At(0, nan, 0)).status().code(),
            absl::StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace hs

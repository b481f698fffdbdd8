#include "common/sim/tool_force.h"

#include <gtest/gtest.h>

#include <cmath>

namespace hs {
namespace {

// k = 1000 N/m, c = 2 N s/m (stiffness_n_per_m, damping_ns_per_m).
Material Steel() {
  Material m;
  m.stiffness_n_per_m = 1000;
  m.damping_ns_per_m = 2;
  return m;
}

// A device 2 mm into a floor (normal +z), still: the spring alone,
// F = k * 0.002 m = 2 N up; touching 10 mm to the side of the tool's
// origin along x, the torque is (0.01, 0, 0) x (0, 0, 2) = (0, -0.02, 0).
TEST(ToolForceTest, SpringAloneByHand) {
  const ToolForce f = SpringDamperForce(
      Steel(),
      ToolContact{
          .p_WD = {0, 0, -0.002}, .p_WP = {0, 0, 0}, .normal_W = {0, 0, 1}, .p_WC = {0.01, 0, 0}},
      10);
  EXPECT_NEAR(f.force_W.x(), 0, 1e-15);
  EXPECT_NEAR(f.force_W.y(), 0, 1e-15);
  EXPECT_NEAR(f.force_W.z(), 2.0, 1e-12);
  EXPECT_NEAR(f.torque_W.x(), 0, 1e-15);
  EXPECT_NEAR(f.torque_W.y(), -0.02, 1e-14);
  EXPECT_NEAR(f.torque_W.z(), 0, 1e-15);
  EXPECT_FALSE(f.clamped);
}

// Pressing in at v = (0.3, 0, -0.5) m/s: only the normal part is damped,
// -c (v . n) n = -2 * (-0.5) * z = +1 N; sliding (x) is not damped here
// (friction is the proxy's). Spring 1 mm: +1 N. Total (0, 0, 2).
TEST(ToolForceTest, DampingAlongTheNormalOnly) {
  const ToolForce f = SpringDamperForce(Steel(),
                                        ToolContact{.p_WD = {0, 0, -0.001},
                                                    .p_WP = {0, 0, 0},
                                                    .v_WD = {0.3, 0, -0.5},
                                                    .normal_W = {0, 0, 1},
                                                    .p_WC = {0, 0, 0}},
                                        10);
  EXPECT_NEAR(f.force_W.x(), 0, 1e-15);
  EXPECT_NEAR(f.force_W.z(), 2.0, 1e-12);
  EXPECT_NEAR(f.torque_W.norm(), 0, 1e-15);  // touching at the origin: no lever
}

// Past the clamp the force keeps its direction at the clamp's length, and
// the torque follows the clamped force: 30 mm at 45 degrees in the x-z
// plane, k = 1000: |F| = 30 N, clamped to 10 N along (1, 0, 1)/sqrt 2.
TEST(ToolForceTest, ClampKeepsTheDirection) {
  const double d = 0.03 / std::sqrt(2.0);
  const ToolForce f = SpringDamperForce(
      Steel(),
      ToolContact{
          .p_WD = {-d, 0, -d}, .p_WP = {0, 0, 0}, .normal_W = {0, 0, 1}, .p_WC = {0, 0.01, 0}},
      10);
  EXPECT_TRUE(f.clamped);
  EXPECT_NEAR(f.force_W.norm(), 10, 1e-12);
  EXPECT_NEAR(f.force_W.x(), 10 / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(f.force_W.z(), 10 / std::sqrt(2.0), 1e-12);
  // (0, 0.01, 0) x (a, 0, a) = (0.01 a, 0, -0.01 a), a = 10 / sqrt 2.
  EXPECT_NEAR(f.torque_W.x(), 0.1 / std::sqrt(2.0), 1e-13);
  EXPECT_NEAR(f.torque_W.z(), -0.1 / std::sqrt(2.0), 1e-13);
}

// The hardest material a face takes (kMaxStiffnessNPerM, kMaxDampingNsPerM)
// at the widest stretch and speed a scene admits (a device 2e6 m into a
// floor at 3.5e10 m/s, its 3.5 km move over a 0.1 ms step) gives a finite
// force: by hand, 1e9 * 2e6 = 2e15 N of spring and 1e9 * 3.5e10 = 3.5e19 N
// of damping, straight up; clamped to 10 N, (0, 0, 10). A 1e308 N/m face
// gave a NaN force, and is refused (material_test).
TEST(ToolForceTest, TheHardestMaterialAtTheWidestMotionStaysFinite) {
  const Material hardest{.stiffness_n_per_m = kMaxStiffnessNPerM,
                         .damping_ns_per_m = kMaxDampingNsPerM};
  const ToolContact contact{.p_WD = {0, 0, -2e6},
                            .p_WP = {0, 0, 0},
                            .v_WD = {0, 0, -3.5e10},
                            .normal_W = {0, 0, 1},
                            .p_WC = {0, 0, 0}};
  const ToolForce unclamped = SpringDamperForce(hardest, contact, 1e300);
  EXPECT_FALSE(unclamped.clamped);
  EXPECT_DOUBLE_EQ(unclamped.force_W.z(), 2e15 + 3.5e19);
  const ToolForce clamped = SpringDamperForce(hardest, contact, 10);
  EXPECT_TRUE(clamped.clamped);
  EXPECT_EQ(clamped.force_W, Vector3d(0, 0, 10));
  EXPECT_TRUE(clamped.torque_W.allFinite());
}

// Device at its proxy and still: no force at all (tiny scales included).
TEST(ToolForceTest, NoStretchNoMotionNoForce) {
  for (double scale : {1e-6, 1.0, 1e3}) {
    const Vector3d p(scale, -scale, 2 * scale);
    const ToolForce f = SpringDamperForce(
        Steel(), ToolContact{.p_WD = p, .p_WP = p, .normal_W = {0, 1, 0}, .p_WC = p * 2}, 10);
    EXPECT_EQ(f.force_W, Vector3d::Zero());
    EXPECT_EQ(f.torque_W, Vector3d::Zero());
    EXPECT_FALSE(f.clamped);
  }
}

// A body that took J = (0, 0, -0.003) N s from the tool in a 1 ms step
// pushes back with -J / dt = (0, 0, 3) N on top of the spring's 2 N; past
// a 4 N clamp the sum (5 N) is scaled to 4 N. No impulse: unchanged.
TEST(ToolForceTest, PushReactionAddsTheImpulseOverTheStep) {
  ToolForce spring;
  spring.force_W = Vector3d(0, 0, 2);
  spring.torque_W = Vector3d(0, -0.02, 0);
  const Vector3d impulse(0, 0, -0.003);
  const ToolForce pushed = WithPushReaction(spring, impulse, 1e-3, 10);
  EXPECT_NEAR(pushed.force_W.z(), 5.0, 1e-12);
  EXPECT_EQ(pushed.torque_W, spring.torque_W);
  EXPECT_FALSE(pushed.clamped);
  const ToolForce clamped = WithPushReaction(spring, impulse, 1e-3, 4);
  EXPECT_NEAR(clamped.force_W.z(), 4.0, 1e-12);
  EXPECT_TRUE(clamped.clamped);
  const ToolForce none = WithPushReaction(spring, Vector3d::Zero(), 1e-3, 1);
  EXPECT_EQ(none.force_W, spring.force_W);
  EXPECT_FALSE(none.clamped);
}

// Two tools' faces meet as springs in series: 1000 and 3000 N/m make
// 1000 * 3000 / 4000 = 750 N/m; dampings 2 and 2 make 1; the friction is
// the touched face's. A face with no damping makes none.
TEST(ToolForceTest, TouchingToolsMeetInSeries) {
  Material touched = Steel();
  touched.stiffness_n_per_m = 3000;
  touched.static_friction = 0.5;
  touched.dynamic_friction = 0.4;
  const Material m = TouchingMaterial(Steel(), touched);
  EXPECT_NEAR(m.stiffness_n_per_m, 750, 1e-12);
  EXPECT_NEAR(m.damping_ns_per_m, 1, 1e-15);
  EXPECT_EQ(m.static_friction, 0.5);
  EXPECT_EQ(m.dynamic_friction, 0.4);
  touched.damping_ns_per_m = 0;
  EXPECT_EQ(TouchingMaterial(Steel(), touched).damping_ns_per_m, 0);
}

// A reaction adds force and torque, and is clamped with the sum.
TEST(ToolForceTest, ReactionAddsForceAndTorque) {
  const ToolForce own{.force_W = {0, 0, 2}, .torque_W = {0, -0.02, 0}};
  const ToolForce sum = WithReaction(own, {.force_W = {3, 0, 0}, .torque_W = {0, 0, 0.01}}, 10);
  EXPECT_EQ(sum.force_W, Vector3d(3, 0, 2));
  EXPECT_EQ(sum.torque_W, Vector3d(0, -0.02, 0.01));
  EXPECT_FALSE(sum.clamped);
  const ToolForce clamped = WithReaction(own, {.force_W = {3, 0, 0}}, 1);
  EXPECT_NEAR(clamped.force_W.norm(), 1, 1e-12);
  EXPECT_TRUE(clamped.clamped);
}

}  // namespace
}  // namespace hs

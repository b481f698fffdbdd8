#include "common/sim/free_body.h"

#include <gtest/gtest.h>

namespace hs {
namespace {

MassProperties UnitCube() {
  MassProperties m;
  m.mass_kg = 1;
  m.I_C = Matrix3d::Identity() / 6;  // 1 m cube of 1 kg
  return m;
}

// Under gravity alone, semi-implicit Euler lands on its closed form
// x_n = x_0 + n h v_0 + g h^2 n (n + 1) / 2, and stays within g h t / 2
// (its first-order lag) of the analytic x_0 + v_0 t + g t^2 / 2.
TEST(FreeBodyTest, FreeFallMatchesAnalytic) {
  const Vector3d g(0, 0, -9.81), v0(0.3, 0, 1);
  const double h = 1e-3;
  FreeBodyState s;
  s.v_W = v0;
  const int n = 500;
  for (int i = 0; i < n; ++i) IntegrateFreeBody(UnitCube(), g, h, s);
  const double t = n * h;
  const Vector3d discrete = n * h * v0 + g * h * h * n * (n + 1) / 2;
  const Vector3d analytic = v0 * t + g * t * t / 2;
  EXPECT_LT((s.X_WO.translation() - discrete).norm(), 1e-12);
  EXPECT_LE((s.X_WO.translation() - analytic).norm(), g.norm() * h * t / 2 + 1e-12);
  EXPECT_LT((s.v_W - (v0 + g * t)).norm(), 1e-12);
}

// Spinning at a constant rate turns the body by w t about w's axis,
// to rounding, and keeps the rotation orthonormal.
TEST(FreeBodyTest, SpinMatchesAnalytic) {
  FreeBodyState s;
  s.w_W = Vector3d(0, 0, 2);
  for (int i = 0; i < 1000; ++i) IntegrateFreeBody(UnitCube(), Vector3d::Zero(), 1e-3, s);
  const Matrix3d expected = Eigen::AngleAxisd(2.0, Vector3d::UnitZ()).toRotationMatrix();
  EXPECT_TRUE(s.X_WO.linear().isApprox(expected, 1e-12));
  EXPECT_TRUE((s.X_WO.linear().transpose() * s.X_WO.linear()).isIdentity(1e-15));
  EXPECT_LT(s.X_WO.translation().norm(), 1e-15);
}

// A body falling onto a fixed surface under its centre of mass is moved
// out by the separation and stops along the normal without spinning.
TEST(FreeBodyTest, ContactStopsApproach) {
  FreeBodyState s;
  s.v_W = Vector3d(0, 0, -1);
  BodyContact c;
  c.normal_W = Vector3d::UnitZ();
  c.p_WC = Vector3d(0, 0, -0.5);
  c.separation_m = 0.01;
  const Vector3d impulse = RespondToContact(UnitCube(), c, s);
  EXPECT_EQ(s.X_WO.translation(), Vector3d(0, 0, 0.01));
  EXPECT_LT(s.v_W.norm(), 1e-15);
  EXPECT_LT(s.w_W.norm(), 1e-15);
  EXPECT_NEAR(impulse.z(), 1, 1e-15);
}

// Friction removes sliding up to mu times the normal impulse; a body
// already leaving the surface takes no impulse.
TEST(FreeBodyTest, FrictionLimitedByCone) {
  FreeBodyState s;
  s.v_W = Vector3d(1, 0, -0.5);
  BodyContact c;
  c.normal_W = Vector3d::UnitZ();
  c.p_WC = Vector3d::Zero();  // at the centre of mass: no spin
  c.friction = 0.4;
  RespondToContact(UnitCube(), c, s);
  EXPECT_NEAR(s.v_W.x(), 1 - 0.4 * 0.5, 1e-15);
  EXPECT_NEAR(s.v_W.z(), 0, 1e-15);
  s.v_W.z() = 0.1;
  const Vector3d leaving = s.v_W;
  EXPECT_EQ(RespondToContact(UnitCube(), c, s), Vector3d::Zero());
  EXPECT_EQ(s.v_W, leaving);
}

// Two equal free bodies meeting head on stop each other (restitution 0):
// momentum is kept.
TEST(FreeBodyTest, TwoBodiesShareImpulse) {
  FreeBodyState a, b;
  a.v_W = Vector3d(1, 0, 0);
  b.v_W = Vector3d(-1, 0, 0);
  b.X_WO.translation() = Vector3d(1, 0, 0);
  const MassProperties m = UnitCube();
  BodyContact c;
  c.normal_W = -Vector3d::UnitX();  // from b toward a
  c.p_WC = Vector3d(0.5, 0, 0);
  RespondToContact(m, c, a, {&m, &b});
  EXPECT_LT(a.v_W.norm(), 1e-15);
  EXPECT_LT(b.v_W.norm(), 1e-15);
}

}  // namespace
}  // namespace hs

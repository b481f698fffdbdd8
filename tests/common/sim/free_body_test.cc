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

}  // namespace
}  // namespace hs

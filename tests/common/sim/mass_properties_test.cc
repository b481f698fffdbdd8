#include "common/sim/mass_properties.h"

#include <gtest/gtest.h>

#include "common/model/procedural.h"

namespace hs {
namespace {

// A box's mass is density x volume and its inertia the textbook solid box's
// m/12 (b^2 + c^2), ...; rounding only (1e-12 relative).
TEST(MassPropertiesTest, BoxMatchesClosedForm) {
  const Vector3d size(0.1, 0.2, 0.3);
  const HapticObject box = *HapticObject::Create("box", MakeBox(size));
  const MassProperties m = *ComputeMassProperties(box, 0, 500);
  const double mass = 500 * size.prod();
  EXPECT_NEAR(m.mass_kg, mass, 1e-12 * mass);
  EXPECT_LT(m.p_OC.norm(), 1e-12);
  const Vector3d s2 = size.cwiseAbs2();
  const Matrix3d expected =
      Vector3d(s2.y() + s2.z(), s2.x() + s2.z(), s2.x() + s2.y()).asDiagonal() * (mass / 12);
  EXPECT_TRUE(m.I_C.isApprox(expected, 1e-12)) << m.I_C;
}

// Moving and turning the mesh moves the centre of mass with it and turns
// the inertia (R I R^T): the same body seen from another frame.
TEST(MassPropertiesTest, FollowsTheMeshFrame) {
  const Vector3d size(0.1, 0.2, 0.3);
  Isometry3d X = Isometry3d::Identity();
  X.linear() = Eigen::AngleAxisd(0.7, Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  X.translation() = Vector3d(0.5, -1, 2);
  const HapticObject a = *HapticObject::Create("a", MakeBox(size));
  const HapticObject b = *HapticObject::Create("b", TransformMesh(MakeBox(size), X));
  const MassProperties ma = *ComputeMassProperties(a, 2, 0);
  const MassProperties mb = *ComputeMassProperties(b, 2, 0);
  EXPECT_DOUBLE_EQ(mb.mass_kg, 2);
  EXPECT_TRUE(mb.p_OC.isApprox(X.translation(), 1e-12));
  EXPECT_TRUE(mb.I_C.isApprox(X.linear() * ma.I_C * X.linear().transpose(), 1e-9));
}

// A fine icosphere is nearly a solid ball: 2/5 m r^2 on each axis, within
// the mesh's volume deficit at 5 subdivisions (under 0.2%).
TEST(MassPropertiesTest, SphereNearBall) {
  const double r = 0.05;
  const HapticObject ball = *HapticObject::Create("ball", MakeIcosphere(r, 5));
  const MassProperties m = *ComputeMassProperties(ball, 1, 0);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(m.I_C(i, i), 0.4 * r * r, 0.002 * 0.4 * r * r);
  EXPECT_LT(m.p_OC.norm(), 1e-12);
}

// Neither a positive mass nor a positive density is an error.
TEST(MassPropertiesTest, RejectsNoMass) {
  const HapticObject box = *HapticObject::Create("box", MakeBox(Vector3d::Ones()));
  EXPECT_EQ(ComputeMassProperties(box, 0, 0).status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(ComputeMassProperties(box, NAN, -1).status().code(),
            absl::StatusCode::kInvalidArgument);
}

// A mass outside [kMinBodyMassKg, kMaxBodyMassKg], given or from the
// density, is an error naming it; the bounds themselves are taken.
TEST(MassPropertiesTest, RejectsMassesOutsideTheBounds) {
  const HapticObject box = *HapticObject::Create("box", MakeBox(Vector3d::Ones()));
  for (const double mass : {1e-300, 0.99 * kMinBodyMassKg, 1.01 * kMaxBodyMassKg, 1e300}) {
    SCOPED_TRACE(mass);
    const absl::StatusOr<MassProperties> given = ComputeMassProperties(box, mass, 0);
    EXPECT_EQ(given.status().code(), absl::StatusCode::kInvalidArgument);
    EXPECT_NE(given.status().message().find("must be in [0.0001, 1e+09] kg"), std::string::npos)
        << given.status();
    // The unit box's volume is 1 m^3: the density is the mass.
    EXPECT_EQ(ComputeMassProperties(box, 0, mass).status().code(),
              absl::StatusCode::kInvalidArgument);
  }
  for (const double mass : {kMinBodyMassKg, kMaxBodyMassKg}) {
    EXPECT_DOUBLE_EQ(ComputeMassProperties(box, mass, 0)->mass_kg, mass);
    EXPECT_DOUBLE_EQ(ComputeMassProperties(box, 0, mass)->mass_kg, mass);
  }
}

}  // namespace
}  // namespace hs

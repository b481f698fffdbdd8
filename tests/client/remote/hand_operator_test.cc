// The simulated operator: its motions' target paths at hand-computed
// times, and the hand as a damped spring pulled toward them and pushed by
// the rendered force, with the work that force does.

#include "client/remote/hand_operator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace hs::cli {
namespace {

constexpr double kDepth = 0.02, kAmplitude = 0.03;

Isometry3d Start() {
  return Eigen::Translation3d(0.1, -0.2, 0.3) * Eigen::AngleAxisd(0.4, Vector3d::UnitY());
}

HandOperator Hand(OperatorMotion motion, HandParams params = {}) {
  return HandOperator(motion, params, Start());
}

// The offset from the start of motion's target at t_s.
Vector3d Offset(OperatorMotion motion, double t_s) {
  return Hand(motion).Target(t_s) - Start().translation();
}

// Each motion's name reads back as it; other names are INVALID_ARGUMENT
// naming what was given.
TEST(HandOperatorTest, NamesRoundTrip) {
  for (const OperatorMotion m :
       {OperatorMotion::kPress, OperatorMotion::kSlide, OperatorMotion::kTap}) {
    const absl::StatusOr<OperatorMotion> parsed = ParseOperator(OperatorName(m));
    ASSERT_TRUE(parsed.ok()) << OperatorName(m);
    EXPECT_EQ(*parsed, m);
  }
  const absl::Status bad = ParseOperator("poke").status();
  EXPECT_EQ(bad.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(bad.message().find("'poke'"), std::string::npos) << bad;
}

// A press: half way down at 0.25 s (a raised cosine is 1/2 at its middle),
// all the way from 0.5 s to 1 s, half way up at 1.25 s, at rest from 1.5 s,
// and again every 2 s; straight down only.
TEST(HandOperatorTest, PressTargets) {
  EXPECT_TRUE(Offset(OperatorMotion::kPress, 0).isZero());
  EXPECT_NEAR(Offset(OperatorMotion::kPress, 0.25).z(), -kDepth / 2, 1e-15);
  EXPECT_NEAR(Offset(OperatorMotion::kPress, 0.5).z(), -kDepth, 1e-15);
  EXPECT_NEAR(Offset(OperatorMotion::kPress, 0.9).z(), -kDepth, 1e-15);
  EXPECT_NEAR(Offset(OperatorMotion::kPress, 1.25).z(), -kDepth / 2, 1e-15);
  EXPECT_NEAR(Offset(OperatorMotion::kPress, 1.75).z(), 0, 1e-15);
  EXPECT_NEAR(Offset(OperatorMotion::kPress, 2.25).z(), -kDepth / 2, 1e-15);
  // One quarter of the way into the descent: (1 - cos(pi/4)) / 2 of the depth.
  EXPECT_NEAR(Offset(OperatorMotion::kPress, 0.125).z(),
              -kDepth * (1 - std::cos(std::numbers::pi / 4)) / 2, 1e-15);
  EXPECT_EQ(Offset(OperatorMotion::kPress, 0.3).head<2>(), Eigen::Vector2d::Zero());
}

// A slide: down by 0.5 s, then x = amplitude * sin(pi (t - 0.5)): +amplitude
// at 1 s, 0 at 1.5 s, -amplitude at 2 s, staying down.
TEST(HandOperatorTest, SlideTargets) {
  EXPECT_NEAR(Offset(OperatorMotion::kSlide, 0.25).z(), -kDepth / 2, 1e-15);
  EXPECT_EQ(Offset(OperatorMotion::kSlide, 0.25).x(), 0);
  EXPECT_TRUE(Offset(OperatorMotion::kSlide, 1).isApprox(Vector3d(kAmplitude, 0, -kDepth), 1e-14));
  EXPECT_NEAR(Offset(OperatorMotion::kSlide, 1.5).x(), 0, 1e-15);
  EXPECT_TRUE(Offset(OperatorMotion::kSlide, 2).isApprox(Vector3d(-kAmplitude, 0, -kDepth), 1e-14));
}

// A tap: all the way down at 0.05 s, back at 0.1 s, half way at 0.025 s and
// again at 0.525 s (every 0.5 s).
TEST(HandOperatorTest, TapTargets) {
  EXPECT_NEAR(Offset(OperatorMotion::kTap, 0.025).z(), -kDepth / 2, 1e-15);
  EXPECT_NEAR(Offset(OperatorMotion::kTap, 0.05).z(), -kDepth, 1e-15);
  EXPECT_NEAR(Offset(OperatorMotion::kTap, 0.1).z(), 0, 1e-15);
  EXPECT_NEAR(Offset(OperatorMotion::kTap, 0.3).z(), 0, 1e-15);
  EXPECT_NEAR(Offset(OperatorMotion::kTap, 0.525).z(), -kDepth / 2, 1e-12);
}

// The device starts where the hand holds it, and keeps the start's
// orientation wherever the hand goes.
TEST(HandOperatorTest, DeviceKeepsTheStartsOrientation) {
  HandOperator hand = Hand(OperatorMotion::kPress);
  EXPECT_TRUE(hand.DevicePose().isApprox(Start()));
  for (int k = 0; k < 300; ++k) hand.Step(k * 1e-3, 1e-3, Vector3d(0, 0, 1));
  EXPECT_EQ(hand.DevicePose().linear(), Start().linear());
  EXPECT_FALSE(hand.DevicePose().translation().isApprox(Start().translation()));
}

// One step from rest on the target under a force F (semi-implicit Euler):
// v = F dt / m, the hand moves v dt, and F does F . v dt of work on it.
TEST(HandOperatorTest, OneStepByHand) {
  const HandParams params{.depth_m = 0, .amplitude_m = 0};
  HandOperator hand = Hand(OperatorMotion::kPress, params);
  const Vector3d force(0.3, 0, -0.6);
  const double dt = 1e-3;
  hand.Step(0, dt, force);
  const Vector3d moved = force / params.mass_kg * dt * dt;
  EXPECT_TRUE(hand.DevicePose().translation().isApprox(Start().translation() + moved, 1e-15));
  EXPECT_NEAR(hand.work_j(), force.dot(moved), 1e-18);
}

// Under a steady force with a still target the hand settles where the
// spring balances it, F / k from the target; the work done is F times the
// displacement (the force is constant).
TEST(HandOperatorTest, SettlesWhereTheSpringBalancesTheForce) {
  // Critically damped: c = 2 sqrt(k m), so it settles within about 0.3 s.
  HandParams params{.depth_m = 0, .amplitude_m = 0};
  params.damping_ns_per_m = 2 * std::sqrt(params.stiffness_n_per_m * params.mass_kg);
  for (const OperatorMotion m :
       {OperatorMotion::kPress, OperatorMotion::kSlide, OperatorMotion::kTap}) {
    HandOperator hand = Hand(m, params);
    const Vector3d force(0.5, -1, 2);
    for (int k = 0; k < 2000; ++k) hand.Step(k * 1e-3, 1e-3, force);
    const Vector3d displacement = hand.DevicePose().translation() - Start().translation();
    EXPECT_TRUE(displacement.isApprox(force / params.stiffness_n_per_m, 1e-9))
        << OperatorName(m) << ": " << displacement.transpose();
    EXPECT_NEAR(hand.work_j(), force.dot(displacement), 1e-12) << OperatorName(m);
  }
}

}  // namespace
}  // namespace hs::cli

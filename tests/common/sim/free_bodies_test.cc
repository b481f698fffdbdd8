// Free bodies (free_bodies.h) through the scene's door: falling, resting,
// pushed by a tool, sub-stepped, stacked, deterministic.
#include "common/sim/free_bodies.h"

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "common/model/procedural.h"
#include "common/sim/mass_properties.h"
#include "common/sim/scene.h"
#include "tests/common/sim/at_pose.h"
#include "tests/common/sim/pinch_rig.h"
#include "tests/common/sim/scene_rig.h"

namespace hs {
namespace {

// With nothing under it, a free body falls on the analytic trajectory
// x0 + v0 t + g t^2 / 2, within semi-implicit Euler's lag g dt t / 2.
TEST(FreeBodiesTest, FreeFallMatchesAnalytic) {
  std::unique_ptr<Scene> scene = *Scene::Create({});
  const Vector3d v0(0.2, 0, 1);
  const ObjectId cube = AddCube(*scene, 1, 0, {.v_W = v0});
  const Vector3d x0 = At(0, 0.05, 1.01).translation();
  const Vector3d g = scene->options().gravity_W;
  const double dt = scene->options().step_s;
  for (int i = 1; i <= 300; ++i) {
    const StepFrame& frame = scene->Step();
    ASSERT_EQ(frame.bodies.size(), 1u);
    EXPECT_EQ(frame.bodies[0].body, cube);
    const double t = i * dt;
    const Vector3d analytic = x0 + v0 * t + g * t * t / 2;
    EXPECT_LE((frame.bodies[0].X_WO.translation() - analytic).norm(), g.norm() * dt * t / 2 + 1e-12)
        << "step " << i;
  }
  EXPECT_GT(scene->stats()[static_cast<int>(Effect::kFreeBodyMotion)].runs, 0);
}

// A free cube dropped 1 cm onto the fixed floor comes to rest on it: from
// then on it penetrates less than the pair's touching tolerance plus one
// step of gravity's fall (g dt^2), and it stays put.
TEST(FreeBodiesTest, FreeBodyRestsOnFixedBox) {
  Rig rig = MakeRig();
  AddCube(*rig.scene, 0.01);
  const double dt = rig.scene->options().step_s;
  for (int i = 0; i < 300; ++i) rig.scene->Step();
  const Isometry3d rest = rig.scene->Step().bodies[0].X_WO;
  const double allowance = 1e-6 + 9.81 * dt * dt;
  for (int i = 0; i < 500; ++i) {
    const BodyFrame& body = rig.scene->Step().bodies[0];
    const double bottom = body.X_WO.translation().z() - 0.01;
    EXPECT_GT(bottom, -allowance) << "step " << i;
    EXPECT_LT(bottom, allowance) << "step " << i;
    EXPECT_GT(body.contacts, 0);
  }
  const Isometry3d after = rig.scene->Step().bodies[0].X_WO;
  EXPECT_LT((after.translation() - rest.translation()).norm(), 1e-6);
  EXPECT_TRUE(after.linear().isApprox(Matrix3d::Identity(), 1e-6));
}

// Two tools of friction `tool_friction` pinch the resting cube from both
// sides, 2 mm into it each, and lift together at 5 cm/s for 1 cm (200
// steps). Returns the cube's last frame; `forces` gets the two devices'
// last forces.
BodyFrame PinchAndLift(double tool_friction, Vector3d forces[2]) {
  PinchRig pinch = MakePinchRig(tool_friction);
  const StepFrame& frame = pinch.PinchAndLift();
  forces[0] = frame.tools[1].force_W;
  forces[1] = frame.tools[2].force_W;
  return frame.bodies[0];
}

// With friction (0.5), the pinched cube rises with the tools and stays
// between them; each device feels its squeeze, equal and opposite, by hand
// 1.0 N (the faces' 500 N/m in series over the 2 mm each jaw is in the
// cube; within 0.1 N: the grip is taken at the depth of the sub-step's
// pose, which the lift's friction tilts a little), and together they carry
// its weight (8 g).
TEST(FreeBodiesTest, TwoToolsPinchAndLiftABox) {
  Vector3d forces[2];
  const double weight = 0.008 * 9.81;
  const BodyFrame lifted = PinchAndLift(0.5, forces);
  EXPECT_GT(lifted.X_WO.translation().z(), 0.01 + 0.0075);  // most of the 1 cm
  EXPECT_NEAR(lifted.v_W.z(), 0.05, 0.005);                 // going up with the jaws
  EXPECT_NEAR(lifted.X_WO.translation().x(), 0.3, 0.0025);  // between them
  EXPECT_NEAR(forces[0].x(), -1.0, 0.1);
  EXPECT_NEAR(forces[1].x(), 1.0, 0.1);
  EXPECT_NEAR(forces[0].z() + forces[1].z(), -weight, 0.1 * weight);
}

// Jaws of friction 0.5 lifting the cube share its weight evenly: each
// device feels half of it (8 g x 9.81 m/s^2 / 2 = 0.039 N) downwards,
// within 10 % (the solver's finite sweeps and the lift's tilt).
TEST(FreeBodiesTest, TwoJawsLiftingShareWeightEvenly) {
  Vector3d forces[2];
  const double half_weight = 0.008 * 9.81 / 2;
  PinchAndLift(0.5, forces);
  EXPECT_NEAR(forces[0].z(), -half_weight, 0.1 * half_weight);
  EXPECT_NEAR(forces[1].z(), -half_weight, 0.1 * half_weight);
}

// With friction 0.01 the jaws can hold 2 x 0.01 x 1.0 N = 0.02 N, less
// than the weight: the cube slides back to the floor, and each device
// feels the 0.01 N it held (500 N/m x 2 mm x 0.01, by hand).
TEST(FreeBodiesTest, JawsWithLittleFrictionLetTheCubeSlip) {
  Vector3d forces[2];
  const BodyFrame slipped = PinchAndLift(0.01, forces);
  EXPECT_NEAR(slipped.X_WO.translation().z(), 0.01, 1e-4);
  EXPECT_NEAR(forces[0].z(), -0.01, 0.002);
  EXPECT_NEAR(forces[1].z(), -0.01, 0.002);
}

// The lightest and the heaviest body a scene takes (kMinBodyMassKg,
// kMaxBodyMassKg; bodies of 1e-300 and 1e300 kg ended their first steps
// with NaN poses, and bodies under 0.1 g pushed this way flew off the
// floor) drop 5 mm onto the floor while the probe pushes into them from
// the side at 0.2 m/s for 60 steps: every step's poses, forces and torques
// are finite, and each body ends on the floor.
TEST(FreeBodiesTest, BodiesAtTheMassBoundsStayFinite) {
  for (const double mass : {kMinBodyMassKg, kMaxBodyMassKg}) {
    SCOPED_TRACE(mass);
    Rig rig = MakeRig();
    AddCube(*rig.scene, 0.005, 0.3, {.mass_kg = mass});
    for (int i = 0; i <= 300; ++i) {
      if (i <= 60) {
        ASSERT_TRUE(rig.scene->SetDevicePose(rig.probe, At(0.279 + 0.0002 * i, 0.05, 0.0101)).ok());
      }
      const StepFrame& frame = rig.scene->Step();
      ASSERT_TRUE(frame.bodies[0].X_WO.matrix().allFinite()) << "step " << i;
      ASSERT_TRUE(frame.tools[0].force_W.allFinite()) << "step " << i;
      ASSERT_TRUE(frame.tools[0].torque_W.allFinite()) << "step " << i;
    }
    EXPECT_NEAR(rig.scene->Step().bodies[0].X_WO.translation().z(), 0.01, 1e-4);
  }
}

// Two jaws of friction `friction`, their bottoms `jaw_bottom` above the
// floor, close 2 mm into each side of the cube resting on the floor (12
// steps) and hold still for 300 steps: after every step the cube's centre
// stays 1 cm above the floor (within 0.1 mm, ten steps of gravity's fall
// g dt^2) and within 1 mm of x = 0.3, between the jaws' faces at 0.292 and
// 0.308, and no step moves it farther than the jaws' 1 mm.
void ExpectSqueezeKeepsCubeOnFloor(double friction, double jaw_bottom) {
  PinchRig pinch = MakePinchRig(friction, 0.015 + jaw_bottom);
  Vector3d before = pinch.frame->bodies[0].X_WO.translation();
  for (int i = 1; i <= 312; ++i) {
    const Vector3d p = pinch.Drive(0.001 * std::min(i, 12), 0).bodies[0].X_WO.translation();
    SCOPED_TRACE(testing::Message() << "friction " << friction << ", jaws " << jaw_bottom
                                    << " m above the floor, step " << i);
    ASSERT_NEAR(p.z(), 0.01, 1e-4);
    ASSERT_NEAR(p.x(), 0.3, 1e-3);
    ASSERT_LE((p - before).norm(), 1e-3);
    before = p;
  }
}

// Squeezing a cube on the floor keeps it there, with and without friction,
// jaws on the floor or above it (the case that threw it 0.56 m sideways and
// through the floor: friction 0.6, jaws on the floor).
TEST(FreeBodiesTest, SqueezedCubeStaysOnFloorBetweenJaws) {
  for (const double friction : {0.6, 0.0}) {
    for (const double jaw_bottom : {0.0, 0.001})
      ExpectSqueezeKeepsCubeOnFloor(friction, jaw_bottom);
  }
}

// A body names what it touched in its step: the floor while it rests;
// both jaws, and not the floor, while they lift it.
TEST(FreeBodiesTest, BodyNamesWhatItTouches) {
  PinchRig pinch = MakePinchRig(0.5);
  EXPECT_EQ(pinch.frame->bodies[0].touching, std::vector<ObjectId>{pinch.rig.floor});
  const BodyFrame& lifted = pinch.PinchAndLift().bodies[0];
  EXPECT_EQ(lifted.touching, (std::vector<ObjectId>{pinch.left, pinch.right}));
}

// The probe pushes a resting free cube sideways: the cube moves along with
// it, ahead of it, and stays on the floor; the device feels it resist.
TEST(FreeBodiesTest, ToolPushesFreeBody) {
  Rig rig = MakeRig();
  // The cube sits on the floor at x = 0.3; the probe, level with it, starts
  // 1 cm to its left and moves 1 mm per step to the right for 60 steps.
  const ObjectId cube = AddCube(*rig.scene, 0);
  for (int i = 0; i < 50; ++i) rig.scene->Step();
  const double x_start = rig.scene->Step().bodies[0].X_WO.translation().x();
  const double probe_x0 = 0.3 - 0.03;
  double push_back = 0;  // the most negative force along the push
  for (int i = 0; i <= 60; ++i) {
    ASSERT_TRUE(rig.scene->SetDevicePose(rig.probe, At(probe_x0 + 0.001 * i, 0.05, 0.0101)).ok());
    const ToolFrame& tool = rig.scene->Step().tools[0];
    push_back = std::min(push_back, tool.force_W.x());
    EXPECT_LE(tool.force_W.norm(), rig.scene->options().force_clamp_n + 1e-12);
  }
  // The device feels the cube resist: the impulse it gave, over the step.
  EXPECT_LT(push_back, 0);
  const StepFrame& frame = rig.scene->Step();
  const BodyFrame& body = frame.bodies[0];
  EXPECT_EQ(body.body, cube);
  // The probe's right face is at probe_x0 + 0.06 + 0.01 at the end; the
  // cube's left face (x - 0.01) must be at or beyond it.
  const double probe_face = probe_x0 + 0.06 + 0.01;
  EXPECT_GT(body.X_WO.translation().x() - 0.01, probe_face - 1e-6);
  EXPECT_GT(body.X_WO.translation().x() - x_start, 0.04);
  EXPECT_NEAR(body.X_WO.translation().z(), 0.01, 1e-4);
}

// A cube thrown down at 30 m/s (3 cm a step, beyond the 5 mm plate's
// thickness) moves in sub-steps under 5 mm and lands on the plate instead
// of passing through it.
TEST(FreeBodiesTest, FastFreeBodySubstepsOntoThinPlate) {
  Rig rig = MakeRig({}, 0.005);
  AddCube(*rig.scene, 0.05, 0.3, {.v_W = Vector3d(0, 0, -30)});
  const BodyFrame& first = rig.scene->Step().bodies[0];
  // 3 cm over the shortest edge (5 mm): 1 + floor(0.03 / 0.005) sub-steps.
  EXPECT_EQ(first.substeps, 7);
  for (int i = 0; i < 20; ++i) rig.scene->Step();
  const BodyFrame& landed = rig.scene->Step().bodies[0];
  EXPECT_NEAR(landed.X_WO.translation().z(), 0.01, 1e-4);  // bottom on the plate's top
  EXPECT_GT(landed.contacts, 0);
}

// A cube dropped onto a cube resting on the floor: the stack holds its
// height (each within 0.1 mm: the bodies part by inverse mass, and a body
// pushed in by the one above is measured out along the floor's normal).
TEST(FreeBodiesTest, StackOfTwoFreeBodiesHolds) {
  Rig rig = MakeRig();
  AddCube(*rig.scene, 0.0, 0.3);
  AddCube(*rig.scene, 0.03, 0.305);
  for (int i = 0; i < 500; ++i) rig.scene->Step();
  const StepFrame& frame = rig.scene->Step();
  EXPECT_NEAR(frame.bodies[0].X_WO.translation().z(), 0.01, 1e-4);
  EXPECT_NEAR(frame.bodies[1].X_WO.translation().z(), 0.03, 1e-4);
}

// Three cubes stacked on the floor (each dropped from 1 mm above the one
// below, the upper two 2 mm off-centre) settle within 500 steps and stay:
// over the next 1,000 steps each centre stays within 0.1 mm of its resting
// height by hand (1, 3, 5 cm; ten steps of gravity's fall g dt^2 each)
// and of where it settled sideways, and turns less than 1 mrad.
TEST(FreeBodiesTest, StackOfThreeSettlesAndStays) {
  Rig rig = MakeRig();
  AddCube(*rig.scene, 0.0, 0.3);
  AddCube(*rig.scene, 0.021, 0.302);
  AddCube(*rig.scene, 0.042, 0.304);
  for (int i = 0; i < 500; ++i) rig.scene->Step();
  const std::vector<BodyFrame> settled = rig.scene->Step().bodies;
  for (int i = 0; i < 1000; ++i) {
    const StepFrame& frame = rig.scene->Step();
    for (int b = 0; b < 3; ++b) {
      const Isometry3d& X = frame.bodies[b].X_WO;
      SCOPED_TRACE(testing::Message() << "cube " << b << ", step " << i);
      ASSERT_NEAR(X.translation().z(), 0.01 + 0.02 * b, 1e-4);
      ASSERT_LT((X.translation() - settled[b].X_WO.translation()).head<2>().norm(), 1e-4);
      ASSERT_LT(Eigen::AngleAxisd(X.linear()).angle(), 1e-3);
    }
  }
}

// A fixed seed for the property below (RC_PARAMS from the environment
// wins, to replay a reported failure), set before RapidCheck reads it.
const bool kSeeded = setenv("RC_PARAMS", "seed=20261128 max_success=25", /*overwrite=*/0) == 0;

// A real in [lo, hi] on a grid of a thousandth of the range.
rc::Gen<double> Real(double lo, double hi) {
  return rc::gen::map(rc::gen::inRange(0, 1001),
                      [lo, hi](int i) { return lo + (hi - lo) * (i / 1000.0); });
}

// Over random squeezes (friction 0 to 1, the jaws' bottoms 0 to 5 mm above
// the floor, each jaw closing 0 to 4 mm into the cube at 0.2 to 1 mm a
// step, then held 50 steps and lifted 0 to 5 mm at 0.05 mm a step), no
// step ends with a corner of the cube deeper in the floor than 2e-5 m (two
// steps of gravity's fall g dt^2), and no step moves the cube's centre
// farther than the farther jaw moved plus 0.5 mm (the two jaws' grips, at
// most 500 N/m x 8 mm, pushing the 8 g cube for a step of 1 ms, move it
// 0.5 mm at most).
RC_GTEST_PROP(FreeBodiesTest, SqueezeNeverDrivesCubeIntoFloor, ()) {
  (void)kSeeded;
  const double friction = *Real(0, 1);
  const double jaw_bottom = *Real(0, 0.005);
  const double left_in = *Real(0, 0.004), right_in = *Real(0, 0.004);
  const double speed = *Real(0.0002, 0.001);
  const double lift = *Real(0, 0.005);
  PinchRig pinch = MakePinchRig(friction, 0.015 + jaw_bottom);
  Vector3d before = pinch.frame->bodies[0].X_WO.translation();
  double left = 0, right = 0, up = 0;
  // The jaws start 1 cm from the cube's faces.
  const double left_end = 0.01 + left_in, right_end = 0.01 + right_in;
  for (int i = 0; i < 200; ++i) {
    const double left_next = std::min(left_end, left + speed);
    const double right_next = std::min(right_end, right + speed);
    const bool closed = left_next == left_end && right_next == right_end;
    const double up_next = closed && i >= 100 ? std::min(lift, up + 0.00005) : up;
    const double jaw_step = std::max({left_next - left, right_next - right, up_next - up});
    left = left_next;
    right = right_next;
    up = up_next;
    const Isometry3d X = pinch.DriveEach(left, right, up).bodies[0].X_WO;
    double lowest = 1;
    for (const double x : {-0.01, 0.01}) {
      for (const double y : {-0.01, 0.01}) {
        for (const double z : {-0.01, 0.01}) lowest = std::min(lowest, (X * Vector3d(x, y, z)).z());
      }
    }
    RC_ASSERT(lowest > -2e-5);
    RC_ASSERT((X.translation() - before).norm() <= jaw_step + 5e-4);
    before = X.translation();
  }
}

// Free bodies move identically, to the bit, for identical inputs.
TEST(FreeBodiesTest, FreeBodiesDeterministic) {
  auto run = [] {
    Rig rig = MakeRig();
    AddCube(*rig.scene, 0.01, 0.1, {.w_W = Vector3d(1, 2, 0)});
    AddCube(*rig.scene, 0.05, 0.105);
    std::vector<Isometry3d> poses;
    for (const Isometry3d& X : PressAndSlide()) {
      EXPECT_TRUE(rig.scene->SetDevicePose(rig.probe, X).ok());
      for (const BodyFrame& b : rig.scene->Step().bodies) poses.push_back(b.X_WO);
    }
    return poses;
  };
  const std::vector<Isometry3d> a = run(), b = run();
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(std::memcmp(a[i].data(), b[i].data(), sizeof(double) * 16), 0) << i;
  }
}

}  // namespace
}  // namespace hs

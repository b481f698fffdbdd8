#include "common/sim/scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "common/model/procedural.h"
#include "tests/common/sim/at_pose.h"
#include "tests/common/sim/scene_rig.h"

namespace hs {
namespace {

std::vector<StepFrame> Drive(Rig& rig, const std::vector<Isometry3d>& path) {
  std::vector<StepFrame> frames;
  for (const Isometry3d& X : path) {
    EXPECT_TRUE(rig.scene->SetDevicePose(rig.probe, X).ok());
    frames.push_back(rig.scene->Step());
  }
  return frames;
}

// A consumer that only needs yes/no collision gets it without any contact
// reconstruction, proxy or force stage running, and its answers equal
// those of a run with everything enabled.
TEST(SceneTest, CollisionOnlyConsumerRunsOnlyCollision) {
  Rig lean = MakeRig(), full = MakeRig();
  lean.scene->SetNeeded({Effect::kCollision});
  const auto a = Drive(lean, PressAndSlide());
  const auto b = Drive(full, PressAndSlide());
  const StageStatsTable& stats = lean.scene->stats();
  EXPECT_EQ(stats[static_cast<int>(Effect::kCollision)].runs, 30);
  for (Effect e : {Effect::kContactSet, Effect::kReversingVector, Effect::kForce}) {
    EXPECT_EQ(stats[static_cast<int>(e)].runs, 0) << EffectName(e);
  }
  int colliding = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].tools[0].contacts.size(), b[i].tools[0].contacts.size()) << "step " << i;
    for (size_t k = 0; k < a[i].tools[0].contacts.size(); ++k) {
      EXPECT_EQ(a[i].tools[0].contacts[k].contact.colliding,
                b[i].tools[0].contacts[k].contact.colliding);
      colliding += a[i].tools[0].contacts[k].contact.colliding;
    }
    EXPECT_EQ(a[i].tools[0].force_W, Vector3d::Zero());
  }
  EXPECT_GT(colliding, 20);
}

// A stage the scene disables never runs, even when needed; stages that
// depend on it do not run either.
TEST(SceneTest, DisabledStageNeverRuns) {
  SceneOptions options;
  options.enabled = EffectSet::All().Without(Effect::kReversingVector);
  Rig rig = MakeRig(options);
  Drive(rig, PressAndSlide());
  for (Effect e : {Effect::kReversingVector, Effect::kForce, Effect::kFriction}) {
    EXPECT_EQ(rig.scene->stats()[static_cast<int>(e)].runs, 0) << EffectName(e);
  }
  EXPECT_GT(rig.scene->stats()[static_cast<int>(Effect::kCollision)].runs, 0);
  EXPECT_GT(rig.scene->stats()[static_cast<int>(Effect::kContactSet)].runs, 0);
}

// The pair caches of the contact set stage live only while it runs and
// the pair is in contact: a consumer that needs no contact sets costs no
// cache, and one that stops needing them frees theirs.
TEST(SceneTest, PairCachesLiveWithTheContactSetStage) {
  Rig lean = MakeRig(), full = MakeRig();
  lean.scene->SetNeeded({Effect::kForce, Effect::kFriction});
  for (const Isometry3d& X : PressAndSlide()) {
    ASSERT_TRUE(lean.scene->SetDevicePose(lean.probe, X).ok());
    lean.scene->Step();
    EXPECT_EQ(lean.scene->pair_caches_held(), 0);
  }
  EXPECT_EQ(Drive(full, PressAndSlide()).back().tools[0].contacts.size(), 1u);
  EXPECT_EQ(full.scene->pair_caches_held(), 1);  // the probe and the floor
  // Lifted off the floor (a step, then one clear of it all along).
  Drive(full, {At(0.15, 0.05, 0.05), At(0.15, 0.05, 0.06)});
  EXPECT_EQ(full.scene->pair_caches_held(), 0);
  Drive(full, {At(0.15, 0.05, 0.015), At(0.15, 0.05, 0.005)});
  EXPECT_EQ(full.scene->pair_caches_held(), 1);
  full.scene->SetNeeded({Effect::kForce});
  Drive(full, {At(0.15, 0.05, 0.004)});
  EXPECT_EQ(full.scene->pair_caches_held(), 0);
}

// A haptic device that needs only its force gets the proxy and the force
// without the collision stage running or the contact sets being
// reconstructed, and both equal those of a run with everything enabled.
TEST(SceneTest, ForceOnlyConsumerSkipsContactSet) {
  Rig lean = MakeRig(), full = MakeRig();
  lean.scene->SetNeeded({Effect::kForce, Effect::kFriction});
  const auto a = Drive(lean, PressAndSlide());
  const auto b = Drive(full, PressAndSlide());
  EXPECT_EQ(lean.scene->stats()[static_cast<int>(Effect::kContactSet)].runs, 0);
  EXPECT_EQ(lean.scene->stats()[static_cast<int>(Effect::kCollision)].runs, 0);
  EXPECT_EQ(lean.scene->stats()[static_cast<int>(Effect::kForce)].runs,
            full.scene->stats()[static_cast<int>(Effect::kForce)].runs);
  int pushing = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].tools[0].X_WP.matrix(), b[i].tools[0].X_WP.matrix()) << "step " << i;
    EXPECT_EQ(a[i].tools[0].force_W, b[i].tools[0].force_W) << "step " << i;
    EXPECT_EQ(a[i].tools[0].torque_W, b[i].tools[0].torque_W) << "step " << i;
    pushing += a[i].tools[0].force_W.norm() > 0;
  }
  EXPECT_GT(pushing, 10);
}

// A scene where nothing moves runs no stage at all.
TEST(SceneTest, NothingMovingSkipsCollision) {
  Rig rig = MakeRig();
  rig.scene->Step();
  const int64_t runs = rig.scene->stats()[static_cast<int>(Effect::kCollision)].runs;
  for (int i = 0; i < 5; ++i) EXPECT_EQ(rig.scene->Step().stages_run, EffectSet());
  EXPECT_EQ(rig.scene->stats()[static_cast<int>(Effect::kCollision)].runs, runs);
}

// Pressed 1 cm into the floor, the proxy stays on the surface and the force
// is the floor's stiffness times the depth, straight up.
TEST(SceneTest, ForceIsSpringToProxy) {
  Rig rig = MakeRig();
  const auto frames = Drive(rig, PressAndSlide());
  const ToolFrame& pressed = frames[19].tools[0];  // probe bottom 1 cm into the floor
  const double depth = -(pressed.X_WD.translation().z() - 0.01);  // probe bottom below z = 0
  ASSERT_GT(depth, 0);
  EXPECT_NEAR(pressed.X_WP.translation().z(), 0.01, 1e-6);  // proxy bottom on the surface
  const double k = Material{}.stiffness_n_per_m;
  // The proxy stands off the surface by 1e-6 of the probe's diagonal.
  EXPECT_NEAR(pressed.force_W.z(), k * depth, k * 1e-6);
  EXPECT_NEAR(pressed.force_W.x(), 0, 1e-9);
  EXPECT_NEAR(pressed.force_W.y(), 0, 1e-9);
}

// Sliding along the floor without friction, the force stays normal and
// continuous: across the diagonal of the floor's top (a face boundary) it
// changes by far less than the clamp between steps.
TEST(SceneTest, SlidingAcrossFaceBoundaryHasNoForceJump) {
  Rig rig = MakeRig();
  std::vector<Isometry3d> path;
  for (int i = 1; i <= 20; ++i) path.push_back(At(0.05, 0.1, 0.02 - 0.0015 * i));
  // Slide along x at y = 0.1 across the diagonal x = y at x = 0.1.
  for (int i = 1; i <= 40; ++i) path.push_back(At(0.05 + 0.0025 * i, 0.1, -0.01));
  SceneOptions options;
  options.enabled = EffectSet::All().Without(Effect::kFriction);
  rig = MakeRig(options);
  const auto frames = Drive(rig, path);
  double largest_jump = 0;
  for (size_t i = 21; i < frames.size(); ++i) {
    largest_jump = std::max(largest_jump,
                            (frames[i].tools[0].force_W - frames[i - 1].tools[0].force_W).norm());
    EXPECT_GT(frames[i].tools[0].force_W.z(), 0) << "step " << i;
  }
  EXPECT_LT(largest_jump, 0.01 * rig.scene->options().force_clamp_n);
}

// The device steps 0.2 m straight through a 5 mm plate in one step: the
// proxy stays on top and the force pushes up (clamped), no pop-through.
TEST(SceneTest, NoPopThroughThinPlate) {
  Rig rig = MakeRig({}, 0.005);
  ASSERT_TRUE(rig.scene->SetDevicePose(rig.probe, At(0.1, 0.05, 0.012)).ok());
  rig.scene->Step();
  ASSERT_TRUE(rig.scene->SetDevicePose(rig.probe, At(0.1, 0.05, -0.19)).ok());
  const ToolFrame& through = rig.scene->Step().tools[0];
  EXPECT_NEAR(through.X_WP.translation().z(), 0.01, 1e-6);
  EXPECT_GT(through.force_W.z(), 0);
  EXPECT_TRUE(through.force_clamped);
  // The next step, still below: the proxy has not popped through.
  ASSERT_TRUE(rig.scene->SetDevicePose(rig.probe, At(0.1, 0.05, -0.2)).ok());
  EXPECT_NEAR(rig.scene->Step().tools[0].X_WP.translation().z(), 0.01, 1e-6);
}

// A device takes the probe over a wall: its proxy follows it around (up,
// over, down). A second device then takes the probe at its home pose, on
// the near side. Seated, its proxy comes from the home pose and the force
// is zero; a pose merely set instead leaves the proxy behind the wall,
// pulling the new device through it at the clamp. A device seated inside
// the floor gets the proxy on the floor's top, as any device would.
TEST(SceneTest, ASeatedDeviceTakesTheProxyFromTheToolsHome) {
  for (const bool seat : {true, false}) {
    SCOPED_TRACE(seat);
    Rig rig = MakeRig();
    ASSERT_TRUE(rig.scene
                    ->AddObject(*HapticObject::Create("wall", MakeBox(Vector3d(0.02, 1, 0.2))),
                                ObjectKind::kFixed, At(0.2, 0, 0.1))
                    .ok());
    const Isometry3d home = At(0.1, 0.05, 0.02);
    std::vector<Isometry3d> around;
    for (int i = 1; i <= 30; ++i) around.push_back(At(0.1, 0.05, 0.02 + 0.01 * i));
    for (int i = 1; i <= 20; ++i) around.push_back(At(0.1 + 0.01 * i, 0.05, 0.32));
    for (int i = 1; i <= 30; ++i) around.push_back(At(0.3, 0.05, 0.32 - 0.01 * i));
    const auto frames = Drive(rig, around);
    ASSERT_NEAR(frames.back().tools[0].X_WP.translation().x(), 0.3, 1e-6);
    ASSERT_TRUE(ApplyDevicePose(*rig.scene, rig.probe, home, seat).ok());
    const ToolFrame& taken = rig.scene->Step().tools[0];
    if (seat) {
      EXPECT_TRUE(taken.X_WP.isApprox(home, 1e-9));
      EXPECT_EQ(taken.force_W, Vector3d::Zero());
    } else {
      EXPECT_GT(taken.X_WP.translation().x(), 0.21);
      EXPECT_TRUE(taken.force_clamped);
    }
  }
  Rig rig = MakeRig();
  ASSERT_TRUE(rig.scene->SeatDevice(rig.probe, At(0.1, 0.05, -0.02)).ok());
  const ToolFrame& inside = rig.scene->Step().tools[0];
  EXPECT_NEAR(inside.X_WP.translation().z(), 0.01, 1e-6);
  EXPECT_GT(inside.force_W.z(), 0);
}

// With friction, a small sideways pull within the static cone leaves the
// proxy stuck and gives a sideways force; without friction it slides.
TEST(SceneTest, StaticFrictionSticks) {
  for (bool friction : {true, false}) {
    SCOPED_TRACE(friction);
    SceneOptions options;
    options.force_clamp_n = 100;  // 20 N of pressing must not be clamped here
    if (!friction) options.enabled = EffectSet::All().Without(Effect::kFriction);
    Rig rig = MakeRig(options);
    std::vector<Isometry3d> path;
    for (int i = 1; i <= 20; ++i) path.push_back(At(0.1, 0.05, 0.02 - 0.0015 * i));
    // 2 cm deep (20 N); pull 1 mm sideways: 1 N against 0.3 x 20 N static.
    path.push_back(At(0.101, 0.05, -0.01));
    const auto frames = Drive(rig, path);
    const ToolFrame& pulled = frames.back().tools[0];
    if (friction) {
      // Within the stand-off's share of the step (1e-6 of the probe's size).
      EXPECT_NEAR(pulled.X_WP.translation().x(), 0.1, 1e-6);
      EXPECT_NEAR(pulled.force_W.x(), -1.0, 1e-3);
    } else {
      EXPECT_NEAR(pulled.X_WP.translation().x(), 0.101, 1e-6);
      EXPECT_NEAR(pulled.force_W.x(), 0, 1e-6);
    }
  }
}

// The same scene and device inputs give bit-identical frames.
TEST(SceneTest, Deterministic) {
  Rig a = MakeRig(), b = MakeRig();
  const auto fa = Drive(a, PressAndSlide());
  const auto fb = Drive(b, PressAndSlide());
  for (size_t i = 0; i < fa.size(); ++i) {
    const ToolFrame& x = fa[i].tools[0];
    const ToolFrame& y = fb[i].tools[0];
    EXPECT_EQ(std::memcmp(x.force_W.data(), y.force_W.data(), sizeof(double) * 3), 0);
    EXPECT_TRUE(x.X_WP.matrix() == y.X_WP.matrix());
    ASSERT_EQ(x.contacts.size(), y.contacts.size());
    for (size_t k = 0; k < x.contacts.size(); ++k) {
      EXPECT_EQ(x.contacts[k].contact.depth_m, y.contacts[k].contact.depth_m);
      EXPECT_EQ(x.contacts[k].contact.moving.vertices, y.contacts[k].contact.moving.vertices);
    }
  }
}

// Bad device poses and ids are rejected with specific codes and change nothing.
TEST(SceneTest, RejectsBadInput) {
  Rig rig = MakeRig();
  EXPECT_EQ(rig.scene->SetDevicePose(rig.probe, At(NAN, 0, 0)).code(),
            absl::StatusCode::kInvalidArgument);
  Isometry3d scaled = At(0, 0, 0);
  scaled.linear() *= 2;
  EXPECT_EQ(rig.scene->SetDevicePose(rig.probe, scaled).code(), absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(rig.scene->SetDevicePose(7, At(0, 0, 0)).code(), absl::StatusCode::kNotFound);
  EXPECT_EQ(rig.scene->SetDevicePose(rig.floor, At(0, 0, 0)).code(),
            absl::StatusCode::kFailedPrecondition);
  const StepFrame& frame = rig.scene->Step();
  EXPECT_TRUE(frame.tools[0].X_WD.isApprox(At(0.1, 0.05, 0.02)));
  EXPECT_EQ(Scene::Create({.step_s = 0}).status().code(), absl::StatusCode::kInvalidArgument);
  for (const double share : {-0.1, 1.5, std::nan("")}) {
    EXPECT_EQ(Scene::Create({.parallel_work_share = share}).status().code(),
              absl::StatusCode::kInvalidArgument)
        << share;
  }
}

// Without continuous collision, the device steps 0.2 m through a 5 mm
// plate in one step, where neither end pose touches it: the step is split
// into sub-steps under the plate's thickness, and the plate is reported
// at the first sub-step that touched.
TEST(SceneTest, SubstepsCatchThinPlateWithoutContinuous) {
  SceneOptions options;
  options.enabled = EffectSet::All().Without(Effect::kContinuousCollision);
  Rig rig = MakeRig(options, 0.005);
  ASSERT_TRUE(rig.scene->SetDevicePose(rig.probe, At(0.1, 0.05, 0.012)).ok());
  EXPECT_EQ(rig.scene->Step().tools[0].substeps, 1);  // 8 mm, under the probe's 2 cm edge
  ASSERT_TRUE(rig.scene->SetDevicePose(rig.probe, At(0.1, 0.05, -0.19)).ok());
  const ToolFrame& through = rig.scene->Step().tools[0];
  // 0.202 m over the 5 mm plate: 1 + floor(0.202 / 0.005) sub-steps.
  EXPECT_EQ(through.substeps, 41);
  ASSERT_EQ(through.contacts.size(), 1u);
  const PairContact& plate = through.contacts[0];
  EXPECT_EQ(plate.object, rig.floor);
  EXPECT_LT(plate.substep, through.substeps);
  EXPECT_TRUE(plate.contact.colliding);
  EXPECT_FALSE(plate.contact.time_of_impact.has_value());
  // The probe's bottom at that sub-step is within one sub-step of the
  // plate's top (z = 0).
  const double bottom = 0.002 - 0.202 * plate.substep / through.substeps;
  EXPECT_LE(bottom, 0);
  EXPECT_GT(bottom, -0.202 / through.substeps - 0.005);
}

// Oracle: on a scene of many objects (a seeded scatter of fixed boxes and
// balls, and free cubes), the broad phase gives exactly the frames of
// testing every pair, with continuous collision on and off (then with
// sub-steps: some steps jump several centimetres).
TEST(SceneTest, BroadPhaseMatchesEveryPair) {
  for (const bool continuous : {true, false}) {
    SCOPED_TRACE(continuous);
    auto run = [continuous](bool broad_phase) {
      SceneOptions options;
      options.broad_phase = broad_phase;
      if (!continuous) options.enabled = EffectSet::All().Without(Effect::kContinuousCollision);
      Rig rig = MakeRig(options);
      std::mt19937 rng(11);
      std::uniform_real_distribution<double> x(0.0, 0.4), size(0.004, 0.03);
      for (int i = 0; i < 40; ++i) {
        const double s = size(rng);
        MeshInput mesh = i % 2 ? MakeBox(Vector3d(s, s, 0.5 * s)) : MakeIcosphere(s / 2, 1);
        EXPECT_TRUE(rig.scene
                        ->AddObject(*HapticObject::Create("o", std::move(mesh)), ObjectKind::kFixed,
                                    At(x(rng), x(rng) - 0.1, s / 4))
                        .ok());
      }
      for (int i = 0; i < 3; ++i) AddCube(*rig.scene, 0.02 * i, x(rng));
      std::vector<StepFrame> frames;
      for (int i = 0; i < 50; ++i) {
        // Sweeps over the scatter, 2 mm per step, with a 6 cm jump every 10th.
        const double along = 0.002 * i + (i / 10) * 0.06;
        EXPECT_TRUE(rig.scene->SetDevicePose(rig.probe, At(along, 0.05 + 0.001 * i, 0.004)).ok());
        frames.push_back(rig.scene->Step());
      }
      return frames;
    };
    const std::vector<StepFrame> fast = run(true), oracle = run(false);
    int contacts = 0, split = 0;
    for (size_t i = 0; i < fast.size(); ++i) {
      const ToolFrame& a = fast[i].tools[0];
      const ToolFrame& b = oracle[i].tools[0];
      EXPECT_EQ(a.substeps, b.substeps);
      split += a.substeps > 1;
      ASSERT_EQ(a.contacts.size(), b.contacts.size()) << "step " << i;
      for (size_t k = 0; k < a.contacts.size(); ++k) {
        EXPECT_EQ(a.contacts[k].object, b.contacts[k].object);
        EXPECT_EQ(a.contacts[k].substep, b.contacts[k].substep);
        EXPECT_EQ(a.contacts[k].contact.depth_m, b.contacts[k].contact.depth_m);
        EXPECT_EQ(a.contacts[k].contact.points.size(), b.contacts[k].contact.points.size());
      }
      contacts += static_cast<int>(a.contacts.size());
      EXPECT_TRUE(a.X_WP.matrix() == b.X_WP.matrix());
      EXPECT_TRUE(a.force_W == b.force_W);
      ASSERT_EQ(fast[i].bodies.size(), oracle[i].bodies.size());
      for (size_t k = 0; k < fast[i].bodies.size(); ++k) {
        EXPECT_TRUE(fast[i].bodies[k].X_WO.matrix() == oracle[i].bodies[k].X_WO.matrix());
      }
    }
    EXPECT_GT(contacts, 20);
    if (!continuous) {
      EXPECT_GT(split, 0);
    }
  }
}

}  // namespace
}  // namespace hs

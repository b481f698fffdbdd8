// The device's haptic loop on hand-made models: a floor, a corner, a
// crest of separating planes, a model past its radius, lost frames and the
// switch bound, bad input; and on a surface (a floor's face and a cube).

#include "client/haptic_loop/haptic_loop.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <random>

namespace hs {
namespace {

constexpr double kK = 1000;  // N/m

ConstraintPlane Plane(const Vector3d& normal, double gap) {
  return {.normal_W = normal.normalized(),
          .gap_m = gap,
          .stiffness_n_per_m = kK,
          .damping_ns_per_m = 0,
          .static_friction = 0,
          .dynamic_friction = 0};
}

// A model at the proxy origin `p` with `planes`, radius 2 cm, clamp 10 N.
LocalModel Model(const Vector3d& p, std::vector<ConstraintPlane> planes) {
  LocalModel m;
  m.X_WP.translation() = p;
  m.validity_radius_m = 0.02;
  m.force_clamp_n = 10;
  m.planes = std::move(planes);
  return m;
}

Isometry3d At(const Vector3d& p) {
  Isometry3d X = Isometry3d::Identity();
  X.translation() = p;
  return X;
}

// A floor 1 mm below the proxy: the device 3 mm down is 2 mm in, pushed
// up by k * 2 mm (hand-computed: 2 N).
TEST(HapticLoopTest, FloorPushesBackBySpringTimesDepth) {
  HapticLoop loop;
  ASSERT_TRUE(loop.SetModel(Model(Vector3d::Zero(), {Plane(Vector3d::UnitZ(), 0.001)})));
  loop.Tick(At(Vector3d::Zero()));
  const HapticOutput out = loop.Tick(At(Vector3d(0, 0, -0.003)));
  EXPECT_TRUE(out.touching);
  EXPECT_NEAR(out.p_WP.z(), -0.001, 1e-7);
  EXPECT_NEAR(out.force_W.z(), 2.0, 1e-3);
  EXPECT_NEAR(out.force_W.x(), 0, 1e-12);
}

// Two walls meeting at a right angle (x >= 0 and y >= 0 for the proxy):
// a device at (-1, -2) mm is held at the corner's edge, the force pulls it
// back along both normals.
TEST(HapticLoopTest, CornerHoldsTheProxyOnBothPlanes) {
  HapticLoop loop({.max_switch_step_n = std::numeric_limits<double>::infinity()});
  ASSERT_TRUE(loop.SetModel(Model(Vector3d(0.001, 0.001, 0), {Plane(Vector3d::UnitX(), 0.001),
                                                              Plane(Vector3d::UnitY(), 0.001)})));
  HapticOutput out;
  for (int i = 0; i < 3; ++i) out = loop.Tick(At(Vector3d(-0.001, -0.002, 0)));
  EXPECT_NEAR(out.p_WP.x(), 0, 1e-7);
  EXPECT_NEAR(out.p_WP.y(), 0, 1e-7);
  EXPECT_NEAR(out.force_W.x(), 1.0, 1e-3);
  EXPECT_NEAR(out.force_W.y(), 2.0, 1e-3);
}

// With friction the proxy sticks while the sideways pull is inside the
// static cone (mu_s * depth) and slides, lagging by mu_d * depth, past it.
TEST(HapticLoopTest, FrictionSticksThenSlides) {
  ConstraintPlane floor = Plane(Vector3d::UnitZ(), 0);
  floor.static_friction = 0.5;
  floor.dynamic_friction = 0.25;
  LocalModel model = Model(Vector3d::Zero(), {floor});
  model.friction = true;
  HapticLoop loop({.max_switch_step_n = std::numeric_limits<double>::infinity()});
  ASSERT_TRUE(loop.SetModel(model));
  loop.Tick(At(Vector3d(0, 0, -0.002)));
  HapticOutput out = loop.Tick(At(Vector3d(0.0009, 0, -0.002)));  // 0.9 mm < 0.5 * 2 mm
  EXPECT_NEAR(out.p_WP.x(), 0, 1e-7);
  out = loop.Tick(At(Vector3d(0.003, 0, -0.002)));  // past the cone: lags by 0.5 mm
  EXPECT_NEAR(out.p_WP.x(), 0.003 - 0.25 * 0.002, 1e-7);
}

// Past the validity radius the proxy stops at the sphere's edge: a floor
// the model knows nothing beyond is not extrapolated 5 cm away.
TEST(HapticLoopTest, ModelIsNotExtrapolatedPastItsRadius) {
  HapticLoop loop;
  ASSERT_TRUE(loop.SetModel(Model(Vector3d::Zero(), {Plane(Vector3d::UnitZ(), 0.001)})));
  const HapticOutput out = loop.Tick(At(Vector3d(0.05, 0, 0)));
  EXPECT_TRUE(out.beyond_validity);
  EXPECT_NEAR(out.p_WP.norm(), 0.02, 1e-9);
  EXPECT_EQ(out.force_W, Vector3d::Zero());
  EXPECT_EQ(loop.beyond_validity_ticks(), 1);
}

// Pressed 2 mm into a floor 3 cm from the model's proxy (past its 2 cm
// radius): the proxy is rendered at the sphere's edge, and the force is the
// floor's push along its normal only (hand-computed: k * 2 mm = 2 N up),
// not a pull back toward the sphere.
TEST(HapticLoopTest, PastItsRadiusOnlyTheNormalPushIsFelt) {
  HapticLoop loop({.max_switch_step_n = std::numeric_limits<double>::infinity()});
  ASSERT_TRUE(loop.SetModel(Model(Vector3d::Zero(), {Plane(Vector3d::UnitZ(), 0)})));
  HapticOutput out;
  for (int i = 0; i <= 30; ++i) out = loop.Tick(At(Vector3d(0.001 * i, 0, -0.002)));
  EXPECT_TRUE(out.beyond_validity);
  EXPECT_NEAR(out.p_WP.norm(), 0.02, 1e-9);
  EXPECT_NEAR(out.force_W.z(), 2.0, 1e-3);
  EXPECT_NEAR(out.force_W.x(), 0, 1e-12);
}

// A model arrives 100 ticks after the pose it was taken at, with the
// server's proxy where the loop's was then: the loop keeps its own proxy,
// where the hand has slid it since, instead of jumping back 1 cm (which
// would drag the hand back by k * 1 cm = 10 N).
TEST(HapticLoopTest, AModelARoundTripOldKeepsTheProxyWhereTheHandTookIt) {
  HapticLoop loop;
  ASSERT_TRUE(loop.SetModel(Model(Vector3d::Zero(), {Plane(Vector3d::UnitZ(), 0)})));
  auto device = [](int tick) { return Vector3d(0.0001 * tick, 0, -0.002); };
  LocalModel late = Model(Vector3d::Zero(), {Plane(Vector3d::UnitZ(), 0)});
  HapticOutput before;
  for (int i = 0; i <= 150; ++i) {
    before = loop.Tick(At(device(i)));
    if (i == 50) {
      late.p_WD = device(i);
      late.X_WP.translation() = before.p_WP;
    }
  }
  ASSERT_TRUE(loop.SetModel(late));
  const HapticOutput after = loop.Tick(At(device(150)));
  EXPECT_NEAR(after.p_WP.x(), before.p_WP.x(), 1e-9);
  EXPECT_NEAR((after.force_W - before.force_W).norm(), 0, 1e-4);  // the stand-off, 2e-8 m
}

// A floor the proxy sticks to (static friction 10), the hand sliding 1 cm
// along it. The server's proxy at tick 50 was 1 mm farther along x than
// the loop's (it knew more of the surface): the loop's proxy moves by that
// 1 mm when the model arrives, and a second model, from tick 60 and
// agreeing with the corrected proxy, moves it no more (the correction is
// not counted twice).
TEST(HapticLoopTest, TheServersCorrectionIsAppliedOnce) {
  ConstraintPlane sticky = Plane(Vector3d::UnitZ(), 0);
  sticky.static_friction = sticky.dynamic_friction = 10;
  LocalModel first = Model(Vector3d::Zero(), {sticky});
  first.friction = true;
  HapticLoop loop({.max_switch_step_n = std::numeric_limits<double>::infinity()});
  ASSERT_TRUE(loop.SetModel(first));
  const Vector3d shift(0.001, 0, 0);
  auto device = [](int tick) { return Vector3d(0.0001 * tick, 0, -0.002); };
  LocalModel second = first;
  HapticOutput out;
  for (int i = 0; i <= 100; ++i) {
    out = loop.Tick(At(device(i)));
    if (i == 50) {
      first.p_WD = device(i);
      first.X_WP.translation() = out.p_WP + shift;
    }
  }
  ASSERT_TRUE(loop.SetModel(first));
  HapticOutput corrected = loop.Tick(At(device(100)));
  // (A stuck proxy creeps by its stand-off, micrometres, each tick.)
  EXPECT_NEAR(corrected.p_WP.x(), out.p_WP.x() + shift.x(), 1e-5);
  // Tick 60 was rendered before the correction arrived; the server's proxy
  // for it agrees with the corrected loop.
  second.p_WD = device(60);
  second.X_WP.translation() = shift;  // the loop's proxy stuck at 0 then
  ASSERT_TRUE(loop.SetModel(second));
  const HapticOutput again = loop.Tick(At(device(100)));
  EXPECT_NEAR(again.p_WP.x(), corrected.p_WP.x(), 1e-5);
}

// Lost frames: the last model keeps rendering the floor. A new model whose
// proxy is 5 mm off (the server's proxy moved) changes the force by 5 N at
// once; the loop spreads it, no tick changing by more than the bound.
TEST(HapticLoopTest, LostFramesKeepTheModelAndSwitchesAreRateBounded) {
  const HapticLoopOptions options{.max_switch_step_n = 0.25};
  HapticLoop loop(options);
  ASSERT_TRUE(loop.SetModel(Model(Vector3d::Zero(), {Plane(Vector3d::UnitZ(), 0)})));
  const Isometry3d pressed = At(Vector3d(0, 0, -0.002));
  HapticOutput last;
  for (int i = 0; i < 20; ++i) last = loop.Tick(pressed);  // the first model ramps in too
  for (int i = 0; i < 50; ++i) {                           // 50 ticks without a frame
    const HapticOutput out = loop.Tick(pressed);
    EXPECT_TRUE(out.touching);
    EXPECT_NEAR(out.force_W.z(), 2.0, 1e-3);
    last = out;
  }
  LocalModel moved = Model(Vector3d(0.005, 0, 0), {Plane(Vector3d::UnitZ(), 0)});
  moved.friction = true;
  moved.planes[0].static_friction = 10;  // sticks where the server left it
  moved.planes[0].dynamic_friction = 10;
  ASSERT_TRUE(loop.SetModel(moved));
  double largest = 0;
  for (int i = 0; i < 60; ++i) {
    const HapticOutput out = loop.Tick(pressed);
    largest = std::max(largest, (out.force_W - last.force_W).norm());
    last = out;
  }
  EXPECT_LE(largest, options.max_switch_step_n + 1e-9);
  EXPECT_NEAR(last.force_W.x(), 5.0, 1e-2);  // it got there (a stuck proxy creeps by its stand-off)
}

// The work a loop's forces do on a device moved along `path` (a tick's
// force times the move to the next tick's position, as on a hand), with
// `switch_at` ticks in a model whose floor is 2 mm higher taken at that
// tick's pose (the server's proxy found above where the loop's was).
double WorkOnPath(HapticLoop& loop, const std::vector<Vector3d>& path, int switch_at) {
  double work = 0;
  Vector3d force = Vector3d::Zero();
  for (int i = 0; i < static_cast<int>(path.size()); ++i) {
    if (i > 0) work += force.dot(path[i] - path[i - 1]);
    if (i == switch_at) {
      LocalModel higher =
          Model(Vector3d(path[i].x(), path[i].y(), 0.002), {Plane(Vector3d::UnitZ(), 0)});
      higher.p_WD = path[i];
      EXPECT_TRUE(loop.SetModel(higher));
    }
    force = loop.Tick(At(path[i])).force_W;
  }
  return work;
}

// 2 mm into a floor over 20 ticks, then back out to 5 mm above it over 40.
std::vector<Vector3d> PressAndLeave() {
  std::vector<Vector3d> path;
  for (int i = 0; i <= 20; ++i) path.emplace_back(0, 0, -0.0001 * i);
  for (int i = 1; i <= 40; ++i) path.emplace_back(0, 0, -0.002 + 0.000175 * i);
  return path;
}

// A model that lifts the floor 2 mm while the device is 2 mm in makes the
// way out harder than the way in: hand-computed, k/2 (4 mm)^2 - k/2 (2 mm)^2
// = 6 mJ handed to the hand. The passivity controller takes it back (to
// within what one tick's prediction misses); without it the 6 mJ stay.
TEST(HapticLoopTest, PassivityControllerTakesBackWhatASwitchGives) {
  const std::vector<Vector3d> path = PressAndLeave();
  HapticLoop free_loop({.max_switch_step_n = std::numeric_limits<double>::infinity(),
                        .max_passivity_damping_ns_per_m = 0});
  ASSERT_TRUE(free_loop.SetModel(Model(Vector3d::Zero(), {Plane(Vector3d::UnitZ(), 0)})));
  EXPECT_NEAR(WorkOnPath(free_loop, path, 20), 0.006, 0.0015);
  EXPECT_EQ(free_loop.passivity_ticks(), 0);

  HapticLoop loop({.max_switch_step_n = std::numeric_limits<double>::infinity()});
  ASSERT_TRUE(loop.SetModel(Model(Vector3d::Zero(), {Plane(Vector3d::UnitZ(), 0)})));
  const double work = WorkOnPath(loop, path, 20);
  EXPECT_LE(work, 1e-4);
  EXPECT_GT(loop.passivity_ticks(), 0);
  EXPECT_GT(loop.passivity_dissipated_j(), 0.004);
}

// A damped floor with friction that stays where it is is passive: the
// controller never acts, and the forces are the uncontrolled loop's tick
// for tick. The slide took about 10 mJ from the hand (friction), but that
// never pays for a kick: when a model then lifts the floor 2 mm under the
// pressed device, the way out hands back at most what the spring held
// before (hand-computed, k/2 (2 mm)^2 = 2 mJ) and the reserve, where the
// uncontrolled loop hands back about k/2 (4 mm)^2 = 8 mJ.
TEST(HapticLoopTest, PassivityControllerLeavesPassiveContactAloneAndFrictionPaysNoKick) {
  ConstraintPlane floor = Plane(Vector3d::UnitZ(), 0);
  floor.damping_ns_per_m = 1;
  floor.static_friction = floor.dynamic_friction = 0.5;
  LocalModel model = Model(Vector3d::Zero(), {floor});
  model.friction = true;
  HapticLoopOptions options;
  HapticLoop controlled(options);
  HapticLoop uncontrolled({.max_passivity_damping_ns_per_m = 0});
  ASSERT_TRUE(controlled.SetModel(model));
  ASSERT_TRUE(uncontrolled.SetModel(model));
  // 2 mm down, then 1 cm along x.
  std::vector<Vector3d> slide;
  for (int i = 0; i <= 20; ++i) slide.emplace_back(0, 0, -0.0001 * i);
  for (int i = 1; i <= 100; ++i) slide.emplace_back(0.0001 * i, 0, -0.002);
  for (const Vector3d& p : slide) {
    EXPECT_EQ(controlled.Tick(At(p)).force_W, uncontrolled.Tick(At(p)).force_W);
  }
  EXPECT_EQ(controlled.passivity_ticks(), 0);

  // Out to 5 mm above, the floor lifted on the first tick.
  std::vector<Vector3d> leave;
  for (int i = 0; i <= 40; ++i) leave.emplace_back(0.01, 0, -0.002 + 0.000175 * i);
  EXPECT_GT(WorkOnPath(uncontrolled, leave, 0), 0.005);
  EXPECT_LE(WorkOnPath(controlled, leave, 0), 0.002 + options.passivity_reserve_j + 1e-4);
  EXPECT_GT(controlled.passivity_ticks(), 0);
}

// A roof of one object, its two slopes 30 degrees down from a ridge along
// y through the origin: planes n1 = (-sin 30, 0, cos 30) and n2 =
// (sin 30, 0, cos 30), the proxy taken 1 mm left of the ridge and 2 mm up.
// The device slides over the ridge and down the right slope to 0.6 mm
// under it. Separating planes (a convex object: in front of either, the
// tool is clear of it) let the proxy follow it down: it ends on the right
// slope over the device, pushing it out by k times its depth along n2
// (hand-computed). Planes that each hold alone keep the proxy on the left
// slope's plane extended past the ridge, well above the device.
LocalModel Roof(bool separating) {
  const double s = 0.5, c = std::sqrt(3.0) / 2;
  const Vector3d p0(-0.001, 0, 0.002);
  std::vector<ConstraintPlane> planes;
  for (const Vector3d& n : {Vector3d(-s, 0, c), Vector3d(s, 0, c)}) {
    ConstraintPlane plane = Plane(n, n.dot(p0));
    plane.object = 3;
    plane.separating = separating;
    planes.push_back(plane);
  }
  return Model(p0, planes);
}

std::vector<Vector3d> OverTheRidge() {
  std::vector<Vector3d> path;
  const Vector3d from(-0.001, 0, 0.002), to(0.01, 0, -0.0064);
  for (int i = 0; i <= 100; ++i) path.push_back(from + (to - from) * (i / 100.0));
  return path;
}

TEST(HapticLoopTest, SeparatingPlanesLetTheProxyDownTheFarSideOfACrest) {
  const Vector3d n2 = Vector3d(0.5, 0, std::sqrt(3.0) / 2);
  HapticOutput out;
  HapticLoop loop({.max_switch_step_n = std::numeric_limits<double>::infinity()});
  ASSERT_TRUE(loop.SetModel(Roof(true)));
  for (const Vector3d& device : OverTheRidge()) out = loop.Tick(At(device));
  const Vector3d device = OverTheRidge().back();
  const double depth = -n2.dot(device);  // behind the right slope
  ASSERT_GT(depth, 0);
  EXPECT_TRUE(out.touching);
  EXPECT_NEAR((out.p_WP - (device + depth * n2)).norm(), 0, 1e-6);
  EXPECT_NEAR((out.force_W - kK * depth * n2).norm(), 0, 1e-3);

  HapticLoop held({.max_switch_step_n = std::numeric_limits<double>::infinity()});
  ASSERT_TRUE(held.SetModel(Roof(false)));
  for (const Vector3d& d : OverTheRidge()) out = held.Tick(At(d));
  const Vector3d n1 = Vector3d(-0.5, 0, std::sqrt(3.0) / 2);
  EXPECT_GE(n1.dot(out.p_WP), -1e-6) << "held in front of the left slope's plane";
  EXPECT_GT(out.force_W.norm(), 3 * kK * depth);
}

// Whatever the device does, the proxy never ends a tick behind every
// separating plane of an object (inside the convex region they bound), nor
// behind a plane of an object without separating planes: random convex
// polytopes of 3-6 separating planes about the proxy, a floor of another
// object below, and random device walks through them.
// Separating planes free the tool of their own object only. A floor and a
// wall of two objects, each plane separating: the device pushed into the
// corner is held on both, as planes that each hold alone hold it (a
// device in front of one object's plane is not free of the other). A
// floor and a wall of one object, the floor separating and the wall not:
// in front of the floor the tool is clear of that object, and the device
// behind the wall's plane is not held by it.
TEST(HapticLoopTest, SeparatingPlanesFreeTheToolOfTheirOwnObjectOnly) {
  auto two_planes = [](int32_t wall_object, bool wall_separating) {
    ConstraintPlane floor = Plane(Vector3d::UnitZ(), 0.001);
    floor.object = 1;
    floor.separating = true;
    ConstraintPlane wall = Plane(Vector3d::UnitX(), 0.001);
    wall.object = wall_object;
    wall.separating = wall_separating;
    return Model(Vector3d(0.001, 0, 0.001), {floor, wall});
  };
  const Vector3d device(-0.001, 0, -0.002);
  HapticLoop two({.max_switch_step_n = std::numeric_limits<double>::infinity()});
  ASSERT_TRUE(two.SetModel(two_planes(2, true)));
  HapticOutput out;
  for (int i = 0; i < 3; ++i) out = two.Tick(At(device));
  EXPECT_NEAR(out.p_WP.x(), 0, 1e-7);
  EXPECT_NEAR(out.p_WP.z(), 0, 1e-7);
  EXPECT_NEAR(out.force_W.x(), 1.0, 1e-3);
  EXPECT_NEAR(out.force_W.z(), 2.0, 1e-3);

  HapticLoop one({.max_switch_step_n = std::numeric_limits<double>::infinity()});
  ASSERT_TRUE(one.SetModel(two_planes(1, false)));
  const Vector3d above_floor(-0.003, 0, 0.0005);
  for (int i = 0; i < 3; ++i) out = one.Tick(At(above_floor));
  EXPECT_NEAR((out.p_WP - above_floor).norm(), 0, 1e-9);
  EXPECT_FALSE(out.touching);
}

TEST(HapticLoopTest, TheProxyStaysClearOfEverySeparatedObject) {
  std::mt19937 rng(7);
  std::normal_distribution<double> gauss(0, 1);
  std::uniform_int_distribution<int> count(3, 6);
  int inside_ticks = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const Vector3d p0 = Vector3d::Zero();
    std::vector<ConstraintPlane> planes;
    // A convex object under the proxy: planes whose normals lean up, each
    // 0.5-3 mm below the proxy.
    const int n = count(rng);
    for (int i = 0; i < n; ++i) {
      const Vector3d normal =
          (Vector3d(gauss(rng), gauss(rng), 0) * 0.6 + Vector3d::UnitZ()).normalized();
      ConstraintPlane plane = Plane(normal, 0.0005 + 0.0025 * std::abs(gauss(rng)) / 2);
      plane.object = 1;
      plane.separating = true;
      planes.push_back(plane);
    }
    ConstraintPlane floor = Plane(Vector3d::UnitZ(), 0.006);
    floor.object = 2;
    planes.push_back(floor);
    HapticLoop loop;
    ASSERT_TRUE(loop.SetModel(Model(p0, planes)));
    Vector3d device = p0;
    for (int tick = 0; tick < 200; ++tick) {
      device += 0.0004 * Vector3d(gauss(rng), gauss(rng), gauss(rng) - 0.3);
      device = device.cwiseMax(Vector3d::Constant(-0.015)).cwiseMin(Vector3d::Constant(0.015));
      const HapticOutput out = loop.Tick(At(device));
      double clear = -std::numeric_limits<double>::infinity();
      for (int i = 0; i < n; ++i) {
        clear = std::max(clear, planes[i].gap_m + planes[i].normal_W.dot(out.p_WP - p0));
      }
      ASSERT_GE(clear, -1e-9) << "trial " << trial << " tick " << tick;
      ASSERT_GE(floor.gap_m + floor.normal_W.dot(out.p_WP - p0), -1e-9)
          << "trial " << trial << " tick " << tick;
      double device_clear = -std::numeric_limits<double>::infinity();
      for (int i = 0; i < n; ++i) {
        device_clear =
            std::max(device_clear, planes[i].gap_m + planes[i].normal_W.dot(device - p0));
      }
      if (device_clear < 0) ++inside_ticks;
    }
  }
  EXPECT_GT(inside_ticks, 1000) << "the walks must go into the objects";
}

TEST(HapticLoopTest, NonFiniteInputNeverReachesTheForce) {
  HapticLoop loop;
  ASSERT_TRUE(loop.SetModel(Model(Vector3d::Zero(), {Plane(Vector3d::UnitZ(), 0)})));
  HapticOutput held;
  for (int i = 0; i < 20; ++i) held = loop.Tick(At(Vector3d(0, 0, -0.001)));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const HapticOutput out = loop.Tick(At(Vector3d(nan, 0, 0)));
  EXPECT_EQ(out.force_W, held.force_W);
  EXPECT_EQ(loop.rejected_poses(), 1);

  LocalModel bad = Model(Vector3d::Zero(), {Plane(Vector3d::UnitZ(), 0)});
  bad.planes[0].normal_W.x() = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(loop.SetModel(bad));
  LocalModel unnormal = Model(Vector3d::Zero(), {Plane(Vector3d::UnitZ(), 0)});
  unnormal.planes[0].normal_W = Vector3d(0, 0, 2);
  EXPECT_FALSE(loop.SetModel(unnormal));
  LocalModel no_radius = Model(Vector3d::Zero(), {});
  no_radius.validity_radius_m = 0;
  EXPECT_FALSE(loop.SetModel(no_radius));
  EXPECT_EQ(loop.rejected_models(), 3);
  // The floor still renders.
  EXPECT_EQ(loop.Tick(At(Vector3d(0, 0, -0.001))).force_W, held.force_W);
}

// A surface of one big floor triangle (its top z = 0, stiffness kK, the
// given friction) with a 2 cm cube as the tool, about `center` within
// `radius`.
std::shared_ptr<ModelSurface> FloorSurface(uint64_t revision, const Vector3d& center, double radius,
                                           double static_friction = 0,
                                           double dynamic_friction = 0) {
  auto s = std::make_shared<ModelSurface>();
  s->revision = revision;
  s->center_W = center;
  s->radius_m = radius;
  for (int i = 0; i < 8; ++i) {
    s->tool_vertices_T.emplace_back(i & 1 ? 0.01 : -0.01, i & 2 ? 0.01 : -0.01,
                                    i & 4 ? 0.01 : -0.01);
  }
  // The cube's faces, two triangles each, counter-clockwise from outside.
  s->tool_triangles = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                       {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  s->vertices_W = {Vector3d(-1, -1, 0), Vector3d(1, -1, 0), Vector3d(0, 1, 0)};
  s->triangles = {{0, 1, 2}};
  s->triangle_materials = {0};
  s->materials = {{.stiffness_n_per_m = kK,
                   .static_friction = static_friction,
                   .dynamic_friction = dynamic_friction}};
  return s;
}

// A model at the server's proxy `p` that shares `surface` (and has a plane
// of its own far away, which the loop on the surface never meets).
LocalModel SurfaceModel(uint64_t revision, const Vector3d& p,
                        std::shared_ptr<const ModelSurface> surface) {
  LocalModel m = Model(p, {Plane(Vector3d::UnitZ(), 0.015)});
  m.revision = revision;
  m.surface = std::move(surface);
  return m;
}

// On a surface the cube rests with its bottom on the floor: the device
// 3 mm under the proxy's rest height is pushed up by k * 3 mm (3 N), and
// the plane of the model, which would hold it 5 mm higher, is not met.
TEST(HapticLoopTest, OnASurfaceTheToolMeetsTheFacesThemselves) {
  HapticLoop loop;
  ASSERT_TRUE(loop.SetModel(
      SurfaceModel(1, Vector3d(0, 0, 0.02), FloorSurface(1, Vector3d(0, 0, 0.02), 0.05))));
  loop.Tick(At(Vector3d(0, 0, 0.02)));
  HapticOutput out;
  for (int i = 0; i < 3; ++i) out = loop.Tick(At(Vector3d(0, 0, 0.007)));
  EXPECT_TRUE(out.touching);
  EXPECT_NEAR(out.p_WP.z(), 0.01, 1e-7);
  EXPECT_NEAR(out.force_W.z(), 3.0, 1e-3);
  // The touching point is the cube's bottom's centre: no torque.
  EXPECT_NEAR(out.torque_W.norm(), 0, 1e-9);
}

// With friction on the surface, a model that arrives from a server whose
// proxy is elsewhere (a round trip behind) changes nothing: the loop's
// proxy stays where the hand has taken it and the force goes on, tick for
// tick the same as a loop that got no new model; a model naming the
// surface alone shares the faces the loop has.
TEST(HapticLoopTest, ModelsOfOneSurfaceLeaveTheProxyWhereItIs) {
  const auto surface = FloorSurface(1, Vector3d(0, 0, 0.01), 0.05, 0.5, 0.25);
  auto named = std::make_shared<ModelSurface>(*surface);
  named->tool_vertices_T.clear();
  named->tool_triangles.clear();
  named->vertices_W.clear();
  named->triangles.clear();
  named->triangle_materials.clear();
  named->materials.clear();
  LocalModel first = SurfaceModel(1, Vector3d(0, 0, 0.01), surface);
  first.friction = true;
  HapticLoop fed, alone;
  ASSERT_TRUE(fed.SetModel(first));
  ASSERT_TRUE(alone.SetModel(first));
  for (int i = 0; i < 400; ++i) {
    const Vector3d device(0.00005 * i, 0.00002 * i, 0.007);
    if (i % 20 == 10) {
      LocalModel later = SurfaceModel(2 + i, Vector3d(0.00005 * (i - 100), 0, 0.0100001), named);
      later.friction = true;
      ASSERT_TRUE(fed.SetModel(later));
    }
    const HapticOutput a = fed.Tick(At(device));
    const HapticOutput b = alone.Tick(At(device));
    ASSERT_EQ(a.force_W, b.force_W) << "tick " << i;
    ASSERT_EQ(a.p_WP, b.p_WP) << "tick " << i;
  }
  EXPECT_EQ(fed.restarted_models(), 0);
  EXPECT_GT(alone.Tick(At(Vector3d(0.02, 0.008, 0.007))).force_W.head<2>().norm(), 0.5)
      << "friction must hold the proxy back";
}

// A model naming a surface the loop never got renders from its planes; a
// proxy inside a new surface's faces (an object moved onto it) restarts at
// the server's proxy.
TEST(HapticLoopTest, AnUnknownSurfaceFallsBackToPlanesAndAnOverlapRestarts) {
  auto named = std::make_shared<ModelSurface>();
  named->revision = 7;
  named->center_W = Vector3d(0, 0, 0.01);
  named->radius_m = 0.05;
  HapticLoop loop;
  ASSERT_TRUE(loop.SetModel(SurfaceModel(1, Vector3d(0, 0, 0.01), named)));
  HapticOutput out;
  for (int i = 0; i < 3; ++i) out = loop.Tick(At(Vector3d(0, 0, -0.01)));
  EXPECT_NEAR(out.p_WP.z(), 0.01 - 0.015, 1e-7) << "held by the model's plane";

  HapticLoop moved;
  ASSERT_TRUE(moved.SetModel(
      SurfaceModel(1, Vector3d(0, 0, 0.03), FloorSurface(1, Vector3d(0, 0, 0.03), 0.05))));
  moved.Tick(At(Vector3d(0, 0, 0.012)));
  // The floor rises 5 mm: the proxy resting 1 cm over the old floor is in it.
  auto risen = FloorSurface(2, Vector3d(0, 0, 0.03), 0.05);
  for (Vector3d& v : risen->vertices_W) v.z() += 0.005;
  ASSERT_TRUE(moved.SetModel(SurfaceModel(2, Vector3d(0, 0, 0.0150001), risen)));
  out = moved.Tick(At(Vector3d(0, 0, 0.012)));
  EXPECT_EQ(moved.restarted_models(), 1);
  EXPECT_NEAR(out.p_WP.z(), 0.0150001, 1e-7);
}

// A model with no planes beside its surface (a device that reads surfaces
// alone) whose faces were lost: the surface the loop holds serves (the
// floor still holds the cube, with the same force); a loop that holds
// none meets nothing and counts its ticks past validity, so that its
// device asks for a fresh model.
TEST(HapticLoopTest, ALostSurfaceWithoutPlanesKeepsTheLastOrAsksForAnother) {
  auto named = std::make_shared<ModelSurface>();
  named->revision = 2;
  named->center_W = Vector3d(0.002, 0, 0.01);
  named->radius_m = 0.05;
  LocalModel first =
      SurfaceModel(1, Vector3d(0, 0, 0.01), FloorSurface(1, Vector3d(0, 0, 0.01), 0.05));
  first.planes.clear();
  LocalModel lost = SurfaceModel(2, Vector3d(0.002, 0, 0.0100001), named);
  lost.planes.clear();
  HapticLoop loop, kept;
  ASSERT_TRUE(loop.SetModel(first));
  ASSERT_TRUE(kept.SetModel(first));
  loop.Tick(At(Vector3d(0, 0, 0.01)));
  kept.Tick(At(Vector3d(0, 0, 0.01)));
  ASSERT_TRUE(loop.SetModel(lost));
  for (int i = 0; i < 5; ++i) {
    const Vector3d device(0.0004 * i, 0, 0.007);
    const HapticOutput a = loop.Tick(At(device));
    const HapticOutput b = kept.Tick(At(device));
    EXPECT_EQ(a.force_W, b.force_W) << i;
    EXPECT_FALSE(a.beyond_validity) << i;
    EXPECT_NEAR(a.force_W.z(), 3.0, 1e-3) << i;
  }
  EXPECT_EQ(loop.beyond_validity_ticks(), 0);

  HapticLoop none;
  ASSERT_TRUE(none.SetModel(lost));
  const HapticOutput out = none.Tick(At(Vector3d(0, 0, 0.007)));
  EXPECT_FALSE(out.touching);
  EXPECT_TRUE(out.beyond_validity);
  EXPECT_EQ(none.beyond_validity_ticks(), 1);
}

TEST(HapticLoopTest, ASurfaceWithABadIndexOrNumberIsRejected) {
  HapticLoop loop;
  auto bad_index = FloorSurface(1, Vector3d::Zero(), 0.05);
  bad_index->triangles[0][2] = 3;
  EXPECT_FALSE(loop.SetModel(SurfaceModel(1, Vector3d::Zero(), bad_index)));
  auto bad_material = FloorSurface(1, Vector3d::Zero(), 0.05);
  bad_material->triangle_materials[0] = 1;
  EXPECT_FALSE(loop.SetModel(SurfaceModel(1, Vector3d::Zero(), bad_material)));
  auto nan = FloorSurface(1, Vector3d::Zero(), 0.05);
  nan->vertices_W[1].y() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(loop.SetModel(SurfaceModel(1, Vector3d::Zero(), nan)));
  auto no_radius = FloorSurface(1, Vector3d::Zero(), 0.05);
  no_radius->radius_m = 0;
  EXPECT_FALSE(loop.SetModel(SurfaceModel(1, Vector3d::Zero(), no_radius)));
  EXPECT_EQ(loop.rejected_models(), 4);
  EXPECT_FALSE(loop.has_model());
}

}  // namespace
}  // namespace hs

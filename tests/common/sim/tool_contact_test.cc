// Tools meet each other (tool_stage.h): a proxy keeps out of the other
// tools' proxies, each tool's frame holds its contact with the others, the
// pushed device feels the pusher's force turned round, and the frames do
// not depend on the number of threads.
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "common/model/procedural.h"
#include "common/sim/scene.h"
#include "tests/common/sim/at_pose.h"
#include "tests/common/sim/same_tool_frame.h"

namespace hs {
namespace {

// 2 cm cubes of the default material (1000 N/m, 1 N s/m): two of them meet
// at 500 N/m and 0.5 N s/m.
constexpr double kPairStiffness = 500;
constexpr double kPairDamping = 0.5;
constexpr double kStepS = 1e-3;

ObjectId AddProbe(Scene& scene, double x, double y = 0) {
  return *scene.AddObject(*HapticObject::Create("probe", MakeBox(Vector3d::Constant(0.02))),
                          ObjectKind::kTool, At(x, y, 0.5));
}

const PairContact* ContactWith(const ToolFrame& frame, ObjectId id) {
  for (const PairContact& pair : frame.contacts) {
    if (pair.object == id) return &pair;
  }
  return nullptr;
}

// Whether two tools' proxies penetrate (more than touch).
bool ProxiesPenetrate(const Scene& scene, const ToolFrame& a, const ToolFrame& b) {
  const auto posed = [&](const ToolFrame& t) {
    const SceneObjects::Object& o = scene.object(t.tool);
    return PosedObject{&o.object, &o.model, t.X_WP};
  };
  const ContactSet contact =
      *ComputeContact(posed(a), posed(b),
                      {.direction_W = b.X_WP.translation() - a.X_WP.translation(),
                       .relative_tolerance = scene.options().relative_tolerance});
  return contact.penetrating;
}

// A is driven 1 mm a step into B, whose device holds still, until A's
// device is 5 mm into B (its face at x = 0.035 + 0.01 against B's at
// 0.04). A's proxy stops on B's face; A feels the spring of the two
// materials in series plus the damping of its 1 m/s approach, by hand:
// F = 500 (P - D) - 0.5 * (v . n) n along x; B feels exactly -F, at the
// touching point; both frames hold the 5 mm contact.
TEST(ToolContactTest, APushIsFeltByBothDevicesEqualAndOpposite) {
  std::unique_ptr<Scene> scene = *Scene::Create({.step_s = kStepS});
  const ObjectId a = AddProbe(*scene, -0.05), b = AddProbe(*scene, 0.05);
  const StepFrame* frame = nullptr;
  for (int i = 1; i <= 85; ++i) {
    ASSERT_TRUE(scene->SetDevicePose(a, At(-0.05 + 0.001 * i, 0, 0.5)).ok());
    frame = &scene->Step();
    ASSERT_EQ(frame->tools.size(), 2u);
    EXPECT_FALSE(ProxiesPenetrate(*scene, frame->tools[0], frame->tools[1])) << "step " << i;
  }
  const ToolFrame& ta = frame->tools[0];
  const ToolFrame& tb = frame->tools[1];
  EXPECT_NEAR(ta.X_WD.translation().x(), 0.035, 1e-12);
  EXPECT_NEAR(ta.X_WP.translation().x(), 0.03, 1e-7);  // on B's face, stood off
  EXPECT_LT(ta.X_WP.translation().x(), 0.03);
  EXPECT_TRUE(tb.X_WP.isApprox(At(0.05, 0, 0.5)));  // B's proxy is not pushed away
  const double spring = kPairStiffness * (ta.X_WP.translation().x() - 0.035);
  const double damping = -kPairDamping * 1.0;  // v = +1 m/s, n = -x: (v . n) n = +x
  EXPECT_NEAR(ta.force_W.x(), spring + damping, 1e-9);
  EXPECT_NEAR(ta.force_W.x(), -3.0, 1e-4);
  EXPECT_NEAR(ta.force_W.y(), 0, 1e-12);
  EXPECT_NEAR(ta.force_W.z(), 0, 1e-12);
  EXPECT_EQ(tb.force_W, -ta.force_W);
  // Each torque is about its own tool's origin from the one touching
  // point p: (p - P_A) x F + (p - P_B) x (-F) = (P_B - P_A) x F, zero for
  // a push along the line of the two origins.
  EXPECT_TRUE((ta.torque_W + tb.torque_W).isZero(1e-15));
  // The contact, in each frame, at the device poses: 5 mm deep.
  const PairContact* ab = ContactWith(ta, b);
  const PairContact* ba = ContactWith(tb, a);
  ASSERT_NE(ab, nullptr);
  ASSERT_NE(ba, nullptr);
  EXPECT_TRUE(ab->contact.penetrating);
  EXPECT_NEAR(ab->contact.depth_m, 0.005, 1e-6);
  EXPECT_NEAR(ba->contact.depth_m, 0.005, 1e-6);
  EXPECT_TRUE(ab->contact.reversing_vector_W.normalized().isApprox(-Vector3d::UnitX(), 1e-6));
  EXPECT_TRUE(ba->contact.reversing_vector_W.normalized().isApprox(Vector3d::UnitX(), 1e-6));
  EXPECT_EQ(ab->contact.fixed.kind, FeatureKind::kFace);
}

// A and B are both driven 1 mm a step into each other: neither proxy
// enters the other, and at every step the two devices feel forces equal
// and opposite, each the sum of its own push and the other's.
TEST(ToolContactTest, PushingEachOtherFeelsEqualAndOpposite) {
  std::unique_ptr<Scene> scene = *Scene::Create({.step_s = kStepS});
  const ObjectId a = AddProbe(*scene, -0.05), b = AddProbe(*scene, 0.05, 0.005);
  int touching = 0;
  for (int i = 1; i <= 50; ++i) {
    ASSERT_TRUE(scene->SetDevicePose(a, At(-0.05 + 0.001 * i, 0, 0.5)).ok());
    ASSERT_TRUE(scene->SetDevicePose(b, At(0.05 - 0.001 * i, 0.005, 0.5)).ok());
    const StepFrame& frame = scene->Step();
    const ToolFrame& ta = frame.tools[0];
    const ToolFrame& tb = frame.tools[1];
    EXPECT_FALSE(ProxiesPenetrate(*scene, ta, tb)) << "step " << i;
    EXPECT_TRUE((ta.force_W + tb.force_W).isZero(1e-12)) << "step " << i;
    if (ta.force_W.x() < 0) ++touching;
  }
  // The devices' faces meet at step 40 (x = 0); then they push.
  EXPECT_GE(touching, 9);
}

// Whether the frame's tools a and b touch: a contact listed, or a proxy
// resting on the other's.
bool Touch(const StepFrame& frame, ObjectId a, ObjectId b) {
  const ToolFrame& ta = frame.tools[0];
  const ToolFrame& tb = frame.tools[1];
  return ContactWith(ta, b) != nullptr || ContactWith(tb, a) != nullptr || ta.touched_tool == b ||
         tb.touched_tool == a;
}

// A goes into B, holds still there, backs out and goes in again: the
// frames count two clashes of the pair, timed over every step they touch,
// the steps A held still included; also when the scene computes forces
// only (a haptic device's needs: no contacts listed, the proxies touch).
class ClashTest : public ::testing::TestWithParam<EffectSet> {};

TEST_P(ClashTest, ClashesAreCountedAndTimed) {
  std::unique_ptr<Scene> scene = *Scene::Create({.step_s = kStepS});
  scene->SetNeeded(GetParam());
  const ObjectId a = AddProbe(*scene, -0.05), b = AddProbe(*scene, 0.05);
  std::vector<double> path;                                         // A's device x, step by step
  for (int i = 1; i <= 83; ++i) path.push_back(-0.05 + 0.001 * i);  // 3 mm in
  for (int i = 0; i < 20; ++i) path.push_back(path.back());         // held
  for (int i = 1; i <= 10; ++i) path.push_back(0.033 - 0.001 * i);  // out
  for (int i = 1; i <= 10; ++i) path.push_back(0.023 + 0.001 * i);  // in again
  int touching_steps = 0;
  const StepFrame* frame = nullptr;
  for (const double x : path) {
    ASSERT_TRUE(scene->SetDevicePose(a, At(x, 0, 0.5)).ok());
    frame = &scene->Step();
    touching_steps += Touch(*frame, a, b);
  }
  ASSERT_EQ(frame->clashes.size(), 1u);
  const ToolClash& clash = frame->clashes[0];
  EXPECT_EQ(clash.tool_a, a);
  EXPECT_EQ(clash.tool_b, b);
  EXPECT_EQ(clash.count, 2);
  EXPECT_GT(touching_steps, 20);
  EXPECT_NEAR(clash.seconds, touching_steps * kStepS, 1e-12);
  EXPECT_TRUE(clash.touching);
}

INSTANTIATE_TEST_SUITE_P(Needs, ClashTest,
                         ::testing::Values(EffectSet::All(),
                                           EffectSet{Effect::kForce, Effect::kFriction}));

constexpr int kPairs = 2;

// Two pairs of probes, far apart, each pair driven into each other, and a
// fifth probe alone, with every effect on; every step on the threads.
std::unique_ptr<Scene> MakePairsScene(int threads) {
  std::unique_ptr<Scene> scene = *Scene::Create({.step_s = kStepS, .parallel_work_share = 0});
  EXPECT_TRUE(scene->SetThreads(threads).ok());
  for (int p = 0; p < kPairs; ++p) {
    AddProbe(*scene, -0.05, 0.3 * p);
    AddProbe(*scene, 0.05, 0.3 * p + 0.004);
  }
  AddProbe(*scene, 0, -0.3);
  return scene;
}

void DriveAll(Scene& scene, int step) {
  for (int p = 0; p < kPairs; ++p) {
    const double speed = 0.001 * (p + 1);
    ASSERT_TRUE(scene.SetDevicePose(2 * p, At(-0.05 + speed * step, 0.3 * p, 0.5)).ok());
    ASSERT_TRUE(
        scene.SetDevicePose(2 * p + 1, At(0.05 - 0.0005 * step, 0.3 * p + 0.004, 0.5)).ok());
  }
  ASSERT_TRUE(scene.SetDevicePose(2 * kPairs, At(0.0001 * step, -0.3, 0.5)).ok());
}

// Stepping the islands on several threads gives bit-identical frames.
TEST(ToolContactTest, ThreadsGiveIdenticalFrames) {
  for (const int threads : {2, 3}) {
    std::unique_ptr<Scene> serial = MakePairsScene(1);
    std::unique_ptr<Scene> parallel = MakePairsScene(threads);
    int pushed_steps = 0;
    for (int step = 1; step <= 60; ++step) {
      DriveAll(*serial, step);
      DriveAll(*parallel, step);
      const StepFrame a = serial->Step();
      const StepFrame& b = parallel->Step();
      ExpectSameToolFrames(a, b);
      for (int t = 0; t < 2 * kPairs; ++t) pushed_steps += a.tools[t].force_W.norm() > 0;
    }
    // The test means something only if both pairs met.
    EXPECT_GT(pushed_steps, 2 * kPairs * 10);
  }
}

// A device seated on a tool whose home another tool's proxy now covers:
// the two proxies start in each other, do not block each other until
// apart, and both reach their devices.
TEST(ToolContactTest, ASeatedDeviceInsideAnotherToolGetsOut) {
  std::unique_ptr<Scene> scene = *Scene::Create({.step_s = kStepS});
  const ObjectId a = AddProbe(*scene, 0), b = AddProbe(*scene, 0.1);
  // A's device leaves home; B's takes A's home place, 1 cm a step.
  for (int i = 1; i <= 10; ++i) {
    ASSERT_TRUE(scene->SetDevicePose(a, At(0, 0.01 * i, 0.5)).ok());
    ASSERT_TRUE(scene->SetDevicePose(b, At(0.1 - 0.01 * i, 0, 0.5)).ok());
    scene->Step();
  }
  // A new device takes A below its home, where B stands: A's proxy comes
  // from home, inside B.
  ASSERT_TRUE(scene->SeatDevice(a, At(0, -0.05, 0.5)).ok());
  const StepFrame* frame = &scene->Step();
  for (int i = 1; i <= 3; ++i) {
    ASSERT_TRUE(scene->SetDevicePose(a, At(0, -0.05 - 0.001 * i, 0.5)).ok());
    frame = &scene->Step();
  }
  EXPECT_TRUE(frame->tools[0].X_WP.isApprox(frame->tools[0].X_WD));
  EXPECT_TRUE(frame->tools[1].X_WP.isApprox(At(0, 0, 0.5)));
  EXPECT_EQ(frame->tools[0].force_W, Vector3d::Zero());
  EXPECT_EQ(frame->tools[1].force_W, Vector3d::Zero());
}

}  // namespace
}  // namespace hs

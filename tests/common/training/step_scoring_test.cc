// A simulation step as the scorer reads it: only the asked tool's part, the
// device's origin (not the proxy's), its force, and its contacts named.

#include "common/training/step_scoring.h"

#include <gtest/gtest.h>

namespace hs {
namespace {

const std::vector<std::string> kNames = {"probe", "organ", "bone", "other probe"};

// A contact with `object` at the given points.
PairContact Touching(ObjectId object, std::vector<Vector3d> points) {
  PairContact c{.object = object};
  for (const Vector3d& p : points) c.contact.points.push_back(ContactPoint{.p_WC = p});
  return c;
}

// Step 7 at 0.014 s: tool 3 first (a decoy with a contact of its own), then
// tool 0 with its device at (1, 2, 3), its proxy held back at (1, 2, 2.5),
// pushed with (0, 0, 4) N, touching the organ at two points and the bone at
// one.
StepFrame Step() {
  StepFrame frame{.step = 7, .time_s = 0.014};
  ToolFrame decoy{.tool = 3};
  decoy.X_WD.translation() = Vector3d(9, 9, 9);
  decoy.force_W = Vector3d(1, 1, 1);
  decoy.contacts.push_back(Touching(2, {Vector3d(9, 9, 8)}));
  frame.tools.push_back(decoy);
  ToolFrame probe{.tool = 0};
  probe.X_WD = Eigen::Translation3d(1, 2, 3) * Eigen::AngleAxisd(0.7, Vector3d::UnitX());
  probe.X_WP.translation() = Vector3d(1, 2, 2.5);
  probe.force_W = Vector3d(0, 0, 4);
  probe.contacts.push_back(Touching(1, {Vector3d(1, 2, 2.4), Vector3d(1.1, 2, 2.4)}));
  probe.contacts.push_back(Touching(2, {Vector3d(0.9, 2, 2.45)}));
  frame.tools.push_back(probe);
  return frame;
}

// The asked tool's part, whatever its place among the tools: time, the
// device origin, force, and each contact named with its points in order;
// nothing of the other tool, and no device time (a step does not have one).
TEST(StepScoringTest, ReadsTheAskedToolsPart) {
  const ScoringFrame f = ScoringFrameFromStep(Step(), 0, kNames);
  EXPECT_EQ(f.time_s, 0.014);
  EXPECT_EQ(f.p_WD, Vector3d(1, 2, 3));
  EXPECT_EQ(f.force_W, Vector3d(0, 0, 4));
  EXPECT_FALSE(f.pose_time_s.has_value());
  ASSERT_EQ(f.contacts.size(), 2u);
  EXPECT_EQ(f.contacts[0].object, "organ");
  EXPECT_EQ(f.contacts[0].points_W, (std::vector<Vector3d>{{1, 2, 2.4}, {1.1, 2, 2.4}}));
  EXPECT_EQ(f.contacts[1].object, "bone");
  EXPECT_EQ(f.contacts[1].points_W, (std::vector<Vector3d>{{0.9, 2, 2.45}}));
  const ScoringFrame decoy = ScoringFrameFromStep(Step(), 3, kNames);
  EXPECT_EQ(decoy.p_WD, Vector3d(9, 9, 9));
  ASSERT_EQ(decoy.contacts.size(), 1u);
  EXPECT_EQ(decoy.contacts[0].object, "bone");
}

// A tool the step lacks (or -1) gives an empty frame at the step's time.
TEST(StepScoringTest, MissingToolIsAnEmptyFrameAtItsTime) {
  for (const ObjectId tool : {ObjectId{1}, ObjectId{-1}}) {
    const ScoringFrame f = ScoringFrameFromStep(Step(), tool, kNames);
    EXPECT_EQ(f.time_s, 0.014);
    EXPECT_EQ(f.p_WD, Vector3d::Zero());
    EXPECT_EQ(f.force_W, Vector3d::Zero());
    EXPECT_TRUE(f.contacts.empty());
  }
}

}  // namespace
}  // namespace hs

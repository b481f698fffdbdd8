// The scorer on short synthetic frame sequences whose metrics are worked
// out by hand in the comments; and the ordering a trainer expects: a gentle
// run beats the same run pressed too hard, and one that touches the table.

#include "common/training/scorer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace hs {
namespace {

constexpr double kDt = 0.001;

// One target on "organ": a 1 cm ball at (0, 0, 0), 1-3 N for 2 ms; the
// table forbidden; the organ limited to 3 N; 1 s to do it.
Exercise OneTarget() {
  Exercise e;
  e.name = "touch";
  e.tool = "probe";
  e.targets = {{.name = "A",
                .object = "organ",
                .region = {Vector3d::Zero(), 0.01},
                .min_force_n = 1,
                .max_force_n = 3,
                .hold_s = 0.002}};
  e.forbidden = {{.object = "table"}};
  e.force_limits = {{.object = "organ", .limit_n = 3}};
  e.time_limit_s = 1;
  return e;
}

ScoringFrame At(int step, const Vector3d& p, double force_z = 0, const char* object = nullptr,
                const Vector3d& point = Vector3d::Zero()) {
  ScoringFrame f{.time_s = step * kDt, .p_WD = p, .force_W = Vector3d(0, 0, force_z)};
  if (object) f.contacts.push_back({object, {point}});
  return f;
}

// Down 1 cm in 10 steps of 1 mm (from z = 0.01 to 0), then three frames
// on the target at 2 N: the hold starts at step 11 and reaches 2 ms at
// step 13. Path 10 mm, shortest 10 mm: economy 1. No forbidden contact,
// no excess; 13 ms is too short for a jerk (sampled every 20 ms).
TEST(ScorerTest, ReachesATargetWithHandComputedMetrics) {
  Scorer scorer(OneTarget());
  for (int i = 0; i <= 10; ++i) scorer.Add(At(i, Vector3d(0, 0, 0.01 - 0.001 * i)));
  EXPECT_FALSE(scorer.done());
  for (int i = 11; i <= 13; ++i) scorer.Add(At(i, Vector3d::Zero(), 2, "organ"));
  ASSERT_TRUE(scorer.done());
  const ScoreSummary s = scorer.Summary();
  EXPECT_TRUE(s.completed);
  EXPECT_EQ(s.targets_reached, 1);
  EXPECT_NEAR(s.duration_s, 0.013, 1e-12);
  EXPECT_NEAR(s.target_results[0].reached_at_s, 0.013, 1e-12);
  EXPECT_NEAR(s.path_length_m, 0.01, 1e-12);
  EXPECT_NEAR(s.economy, 1, 1e-9);
  EXPECT_EQ(s.max_force_n, 2);
  EXPECT_EQ(s.forbidden_contacts, 0);
  EXPECT_EQ(s.excess_impulse_ns, 0);
  // Positions at 0, 20 ms, ...: one sample (steps 0 and ... 13 ms): no jerk.
  EXPECT_EQ(s.jerk_rms, 0);
  const double smooth = 1;
  EXPECT_NEAR(s.score, (50 + 10 * 0.987 + 10 + 15 + 10 + 5 * smooth), 1e-9);
}

// The run above from a server stepping at half pace, each pose applied
// two steps late, with the device's clock in its frames: the hold, the
// duration and the time of the target are the device's (13 ms, the
// figures above), not the frames' (26 ms apart).
TEST(ScorerTest, TimesAreTheDevicesClockWhenFramesCarryIt) {
  Scorer scorer(OneTarget());
  auto late = [](ScoringFrame f) {
    f.pose_time_s = f.time_s;
    f.time_s = 2 * f.time_s + 2 * kDt;
    return f;
  };
  for (int i = 0; i <= 10; ++i) scorer.Add(late(At(i, Vector3d(0, 0, 0.01 - 0.001 * i))));
  for (int i = 11; i <= 13; ++i) scorer.Add(late(At(i, Vector3d::Zero(), 2, "organ")));
  ASSERT_TRUE(scorer.done());
  const ScoreSummary s = scorer.Summary();
  EXPECT_NEAR(s.duration_s, 0.013, 1e-12);
  EXPECT_NEAR(s.target_results[0].reached_at_s, 0.013, 1e-12);
  EXPECT_NEAR(s.path_length_m, 0.01, 1e-12);
  EXPECT_NEAR(s.score, 50 + 10 * 0.987 + 10 + 15 + 10 + 5, 1e-9);
}

// Frames that repeat the pose of a device time already scored add no time
// and no path: the hold of 2 ms needs two more milliseconds of poses.
TEST(ScorerTest, RepeatedDeviceTimeAddsNoTime) {
  Scorer scorer(OneTarget());
  auto stamped = [](ScoringFrame f, double pose_s) {
    f.pose_time_s = pose_s;
    return f;
  };
  scorer.Add(stamped(At(0, Vector3d(0, 0, 0.001)), 0));
  for (int i = 1; i <= 5; ++i) scorer.Add(stamped(At(i, Vector3d::Zero(), 2, "organ"), 0.001));
  EXPECT_FALSE(scorer.done());
  EXPECT_EQ(scorer.progress().elapsed_s, 0.001);
  scorer.Add(stamped(At(6, Vector3d::Zero(), 2, "organ"), 0.002));
  EXPECT_FALSE(scorer.done());
  scorer.Add(stamped(At(7, Vector3d::Zero(), 2, "organ"), 0.003));
  ASSERT_TRUE(scorer.done());
  EXPECT_NEAR(scorer.Summary().duration_s, 0.003, 1e-12);
  EXPECT_NEAR(scorer.Summary().path_length_m, 0.001, 1e-12);
}

// The same run after 500 steps resting at the tool's home (z = 0.01): the
// clock starts at the first frame away from home (step 501, 1 mm down),
// so the hand-computed figures are those of the run above less the first
// frame: 12 ms, 9 mm of path from the start at z = 0.009.
TEST(ScorerTest, ClockStartsAtTheFirstMotionFromHome) {
  Exercise e = OneTarget();
  e.tool_home_W = Vector3d(0, 0, 0.01);
  Scorer scorer(e);
  for (int i = 0; i <= 500; ++i) scorer.Add(At(i, Vector3d(0, 0, 0.01)));
  EXPECT_EQ(scorer.progress().elapsed_s, 0);
  for (int i = 1; i <= 10; ++i) scorer.Add(At(500 + i, Vector3d(0, 0, 0.01 - 0.001 * i)));
  for (int i = 11; i <= 13; ++i) scorer.Add(At(500 + i, Vector3d::Zero(), 2, "organ"));
  ASSERT_TRUE(scorer.done());
  const ScoreSummary s = scorer.Summary();
  EXPECT_NEAR(s.duration_s, 0.012, 1e-12);
  EXPECT_NEAR(s.path_length_m, 0.009, 1e-12);
  EXPECT_NEAR(s.economy, 1, 1e-9);
  EXPECT_EQ(scorer.trace().size(), 13u);
}

// z = a t^3: its jerk is 6a everywhere, and a third difference of a cubic
// is exact, so the rms is 6a (a = 2 m/s^3: 12 m/s^3).
TEST(ScorerTest, JerkOfACubicIsSixTimesItsCoefficient) {
  Exercise e = OneTarget();
  Scorer scorer(e);
  constexpr double a = 2;
  for (int i = 0; i <= 300; ++i) {
    const double t = i * kDt;
    scorer.Add(At(i, Vector3d(0, 0, 0.05 + a * t * t * t)));
  }
  EXPECT_NEAR(scorer.Summary().jerk_rms, 6 * a, 1e-6);
}

// A device's samples of p(t) = p0 + c t^3 at irregular times of its own
// clock (every 5 ms, each moved by up to 2 ms), delivered through frames
// at 1 ms steps after a delay of 30-40 ms (in order): each frame carries
// the newest pose come in, so poses repeat over frames, and one that comes
// in with the next within a step is never seen. Seed 7.
struct CubicRun {
  Vector3d p0 = Vector3d(0, 0, 0.05);
  Vector3d c = Vector3d(1, -2, 0.5);  // m/s^3: the jerk is 6c everywhere
  std::vector<ScoringFrame> frames;
  // The poses the frames carry, once each, in order.
  std::vector<Vector3d> seen;
};

CubicRun Cubic() {
  CubicRun run;
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> shift(-0.002, 0.002), delay(0.030, 0.040);
  std::vector<double> made, arrives;
  for (int i = 0; i < 100; ++i) {
    made.push_back(0.005 * i + shift(random));
    arrives.push_back(std::max(made.back() + delay(random), arrives.empty() ? 0 : arrives.back()));
  }
  // The last pose comes in by 0.54 s.
  size_t next = 0;
  for (int k = 0; k <= 600; ++k) {
    const double step_s = 0.001 * k;
    const size_t before = next;
    while (next < made.size() && arrives[next] <= step_s) ++next;
    if (next == 0) continue;
    const double t = made[next - 1];
    run.frames.push_back({.time_s = step_s, .p_WD = run.p0 + run.c * t * t * t, .pose_time_s = t});
    if (next != before) run.seen.push_back(run.frames.back().p_WD);
  }
  return run;
}

// Timed by the device's clock, the jerk of a cubic sampled at irregular
// times and delivered late and unevenly is still 6c (a third divided
// difference is exact for a cubic), and the path is that of the poses
// seen, once each; timed by the frames instead, the jerk is far off.
TEST(ScorerTest, JerkOfACubicOnTheDevicesClockIgnoresDelivery) {
  Exercise e = OneTarget();
  e.time_limit_s = 10;
  const CubicRun run = Cubic();
  ASSERT_LT(run.seen.size(), 100u) << "some pose must be lost to delivery";
  Scorer device(e), frames(e);
  for (const ScoringFrame& f : run.frames) {
    device.Add(f);
    ScoringFrame untimed = f;
    untimed.pose_time_s.reset();
    frames.Add(untimed);
  }
  double path = 0;
  for (size_t i = 1; i < run.seen.size(); ++i) path += (run.seen[i] - run.seen[i - 1]).norm();
  const ScoreSummary s = device.Summary();
  EXPECT_NEAR(s.jerk_rms, 6 * run.c.norm(), 1e-6 * run.c.norm());
  EXPECT_NEAR(s.path_length_m, path, 1e-12);
  EXPECT_GT(std::abs(frames.Summary().jerk_rms - 6 * run.c.norm()), 3 * run.c.norm());
}

// A device clock of 0 is a device that does not stamp its poses: no time.
TEST(ScorerTest, DevicePoseTimeOfZeroIsNone) {
  EXPECT_FALSE(DevicePoseTime(0).has_value());
  EXPECT_EQ(DevicePoseTime(1'500'000'000), 1.5);
}

// A break in the hold starts it again; force out of range does not hold.
TEST(ScorerTest, HoldMustBeUnbroken) {
  Scorer scorer(OneTarget());
  scorer.Add(At(0, Vector3d::Zero(), 2, "organ"));
  scorer.Add(At(1, Vector3d::Zero(), 2, "organ"));
  scorer.Add(At(2, Vector3d::Zero(), 4, "organ"));  // above 3 N: breaks, and exceeds
  scorer.Add(At(3, Vector3d::Zero(), 2, "organ"));
  scorer.Add(At(4, Vector3d::Zero(), 2, "organ"));
  EXPECT_FALSE(scorer.done());
  scorer.Add(At(5, Vector3d::Zero(), 2, "organ"));
  EXPECT_TRUE(scorer.done());
  const ScoreSummary s = scorer.Summary();
  EXPECT_NEAR(s.force_limit_exceeded_s, 0.001, 1e-12);
  EXPECT_NEAR(s.excess_impulse_ns, 1 * 0.001, 1e-12);  // (4 - 3) N for 1 ms
}

// Touching the table twice (two runs of frames) is two forbidden contacts,
// with their durations and largest forces; a point outside the target's
// ball does not touch the target.
TEST(ScorerTest, ForbiddenContactsCountByRun) {
  Scorer scorer(OneTarget());
  scorer.Add(At(0, Vector3d::Zero(), 1, "table"));
  scorer.Add(At(1, Vector3d::Zero(), 5, "table"));
  scorer.Add(At(2, Vector3d::Zero()));
  scorer.Add(At(3, Vector3d::Zero(), 2, "table"));
  for (int i = 4; i < 10; ++i)
    scorer.Add(At(i, Vector3d::Zero(), 2, "organ", Vector3d(0.02, 0, 0)));
  const ScoreSummary s = scorer.Summary();
  ASSERT_EQ(s.forbidden_contacts, 2);
  EXPECT_NEAR(s.forbidden_list[0].duration_s, 0.001, 1e-12);
  EXPECT_EQ(s.forbidden_list[0].max_force_n, 5);
  EXPECT_NEAR(s.forbidden_list[1].start_s, 0.003, 1e-12);
  EXPECT_EQ(s.targets_reached, 0);
  EXPECT_FALSE(s.completed);
  EXPECT_EQ(scorer.progress().errors, 2);
}

// Frames past the time limit are not scored, and end the exercise.
TEST(ScorerTest, TimeLimitEndsIt) {
  Exercise e = OneTarget();
  e.time_limit_s = 0.005;
  Scorer scorer(e);
  for (int i = 0; i < 5; ++i) scorer.Add(At(i, Vector3d(0.001 * i, 0, 0.01)));
  EXPECT_FALSE(scorer.done());
  scorer.Add(At(6, Vector3d(1, 0, 0.01)));
  EXPECT_TRUE(scorer.done());
  const ScoreSummary s = scorer.Summary();
  EXPECT_NEAR(s.path_length_m, 0.004, 1e-12);
  EXPECT_NEAR(s.duration_s, 0.004, 1e-12);
  EXPECT_FALSE(s.completed);
}

// The same gentle run scores higher than pressed past the limit, and
// higher than with a touch of the forbidden table.
TEST(ScorerTest, GentleBeatsPressedAndForbidden) {
  auto run = [](double force, bool table) {
    Scorer scorer(OneTarget());
    for (int i = 0; i <= 10; ++i) scorer.Add(At(i, Vector3d(0, 0, 0.01 - 0.001 * i)));
    if (table) scorer.Add(At(11, Vector3d::Zero(), 1, "table"));
    for (int i = 12; i < 40; ++i) scorer.Add(At(i, Vector3d::Zero(), force, "organ"));
    for (int i = 40; i < 45; ++i) scorer.Add(At(i, Vector3d::Zero(), 2, "organ"));
    return scorer.Summary();
  };
  const ScoreSummary gentle = run(2, false), pressed = run(6, false), table = run(2, true);
  EXPECT_TRUE(gentle.completed && pressed.completed && table.completed);
  EXPECT_GT(gentle.score, pressed.score);
  EXPECT_GT(gentle.score, table.score);
  EXPECT_GT(pressed.excess_impulse_ns, 0);
}

}  // namespace
}  // namespace hs

#include "server/step_pacer.h"

#include <gtest/gtest.h>

namespace hs {
namespace {

// Periods of 1,000 ns: every reading below is hand-placed against them.
constexpr int64_t kPeriod = 1000;

// On time, steps come each period; none starts before 3/4 of one.
TEST(StepPacerTest, StepsEachPeriod) {
  StepPacer pacer(kPeriod, 0, 0);
  EXPECT_EQ(pacer.earliest_ns(), 750);
  EXPECT_EQ(pacer.deadline_ns(), 1000);
  const StepPacer::Start start = pacer.StepStarts(1000, 100, false);
  EXPECT_EQ(start.lag_ns, 0);
  EXPECT_EQ(start.missed, 0);
  EXPECT_EQ(pacer.earliest_ns(), 1750);
  EXPECT_EQ(pacer.deadline_ns(), 2000);
}

// A start late by less than a period, or by exactly one, misses nothing
// and keeps the phase; the lag is reported.
TEST(StepPacerTest, LateByUpToAPeriodMissesNothing) {
  StepPacer pacer(kPeriod, 0, 0);
  StepPacer::Start start = pacer.StepStarts(1400, 100, false);
  EXPECT_EQ(start.lag_ns, 400);
  EXPECT_EQ(start.missed, 0);
  EXPECT_EQ(pacer.deadline_ns(), 2000);
  start = pacer.StepStarts(3000, 200, false);
  EXPECT_EQ(start.lag_ns, 1000);
  EXPECT_EQ(start.missed, 0);
  EXPECT_EQ(pacer.deadline_ns(), 3000);
}

// Late by 3.5 periods: three steps are missed (skipped, not run), and the
// next deadline is the first one after the start, in the old phase.
TEST(StepPacerTest, LateStartSkipsTheMissedSteps) {
  StepPacer pacer(kPeriod, 0, 0);
  const StepPacer::Start start = pacer.StepStarts(4500, 100, false);
  EXPECT_EQ(start.lag_ns, 3500);
  EXPECT_EQ(start.missed, 3);
  EXPECT_EQ(pacer.deadline_ns(), 5000);
}

// The off-CPU rule: less than a period of CPU since the last start, after
// a step shorter than a period, is off the CPU; a thread that used a
// period of CPU, or whose last step itself took a period, was stepping.
TEST(StepPacerTest, OffTheCpuOnlyWhenNeitherComputingNorStepping) {
  {
    StepPacer pacer(kPeriod, 0, 0);
    pacer.StepEnded(300);
    const StepPacer::Start start = pacer.StepStarts(5200, 999, false);
    EXPECT_EQ(start.missed, 4);
    EXPECT_TRUE(start.off_cpu);
  }
  {
    StepPacer pacer(kPeriod, 0, 0);
    pacer.StepEnded(300);
    EXPECT_FALSE(pacer.StepStarts(5200, 1000, false).off_cpu);  // a period of CPU
  }
  {
    StepPacer pacer(kPeriod, 0, 0);
    pacer.StepEnded(1000);  // the last step took a period (its workers' share)
    EXPECT_FALSE(pacer.StepStarts(5200, 10, false).off_cpu);
  }
  {
    // CPU counts from the last start, not from the runner's.
    StepPacer pacer(kPeriod, 0, 0);
    pacer.StepStarts(1000, 5000, false);
    pacer.StepEnded(100);
    const StepPacer::Start start = pacer.StepStarts(4100, 5200, false);
    EXPECT_EQ(start.missed, 2);
    EXPECT_TRUE(start.off_cpu);
  }
}

// Devices that came before the deadline start the step at once (no lag),
// set the phase, and leave a quarter period for a late device: the next
// deadline is a period and a quarter after that start.
TEST(StepPacerTest, DevicesClockTheSteps) {
  StepPacer pacer(kPeriod, 0, 0);
  const StepPacer::Start start = pacer.StepStarts(800, 50, true);
  EXPECT_EQ(start.lag_ns, 0);
  EXPECT_EQ(start.missed, 0);
  EXPECT_EQ(pacer.earliest_ns(), 1550);
  EXPECT_EQ(pacer.deadline_ns(), 2050);
  // A device that went silent: the scene falls back on its own period.
  pacer.StepStarts(2050, 100, false);
  EXPECT_EQ(pacer.deadline_ns(), 3050);
}

// The start: at the deadline while a device has not sent, at 3/4 of a
// period once all have; never before 3/4 of a period, late or not.
TEST(StepPacerTest, StartIsTheDeadlineOrEarlierForFreshDevices) {
  StepPacer pacer(kPeriod, 0, 0);
  EXPECT_EQ(pacer.start_ns(false), 1000);
  EXPECT_EQ(pacer.start_ns(true), 750);
  // Late by 3.5 periods: the next deadline (5000) comes before 3/4 of a
  // period from this start (5250), which is when the next step starts.
  pacer.StepStarts(4500, 100, false);
  EXPECT_EQ(pacer.deadline_ns(), 5000);
  EXPECT_EQ(pacer.start_ns(false), 5250);
  EXPECT_EQ(pacer.start_ns(true), 5250);
  // Then on time, and the devices clock a step: the next deadline is a
  // period and a quarter after it, the earliest start 3/4 of a period.
  pacer.StepStarts(5250, 200, false);
  EXPECT_EQ(pacer.start_ns(false), 6000);
  pacer.StepStarts(6000, 300, true);
  EXPECT_EQ(pacer.start_ns(false), 7250);
  EXPECT_EQ(pacer.start_ns(true), 6750);
}

}  // namespace
}  // namespace hs

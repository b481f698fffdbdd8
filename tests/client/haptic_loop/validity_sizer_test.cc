// The validity radius a device asks for: the hand's travel in a round trip
// and a model period, times the safety factor, on the ladder, within the
// bounds; peaks remembered for a window and then forgotten.

#include "client/haptic_loop/validity_sizer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace hs {
namespace {

// A hand moving along x at `speed` for `seconds` from t = `t0`, sampled at 1 kHz.
void Move(ValiditySizer& sizer, double t0, double seconds, double speed) {
  for (int k = 0; k <= static_cast<int>(std::lround(seconds * 1e3)); ++k) {
    const double t = t0 + k * 1e-3;
    sizer.AddDevicePosition(t, Vector3d(speed * t, 0, 0));
  }
}

// The ladder's rung at or above `travel`: min * 2^(k/4), by hand.
double Rung(double travel, double min_m) {
  double r = min_m;
  while (r < travel * (1 - 1e-12)) r *= std::pow(2.0, 0.25);
  return r;
}

// Until both a speed and a round trip are known the most is wanted.
TEST(ValiditySizerTest, WantsTheMostUntilItKnowsSpeedAndRoundTrip) {
  ValiditySizer sizer({.max_m = 0.04});
  EXPECT_EQ(sizer.WantedRadius(), 0.04);
  Move(sizer, 0, 0.1, 0.01);
  EXPECT_EQ(sizer.WantedRadius(), 0.04);
  sizer.AddRoundTrip(0.1, 0.1);
  EXPECT_LT(sizer.WantedRadius(), 0.04);
}

// 0.1 m/s over a 100 ms round trip and a 50 ms model period, times 1.5:
// 22.5 mm, on the ladder's next rung.
TEST(ValiditySizerTest, CoversTheTravelOfARoundTripAndAModelPeriod) {
  ValiditySizer sizer;
  Move(sizer, 0, 0.2, 0.1);
  sizer.AddRoundTrip(0.2, 0.1);
  const double travel = 0.1 * (0.1 + 0.05) * 1.5;
  EXPECT_NEAR(sizer.peak_speed_m_per_s(), 0.1, 1e-9);  // exact samples, rounding only
  EXPECT_DOUBLE_EQ(sizer.peak_round_trip_s(), 0.1);
  EXPECT_GE(sizer.WantedRadius(), travel);
  EXPECT_NEAR(sizer.WantedRadius(), Rung(travel, 1e-3), 1e-12);
  EXPECT_LT(sizer.WantedRadius(), travel * std::pow(2.0, 0.25));
}

// A still hand is taken to reach the least speed at once (0.1 m/s over
// 350 ms, times 1.5: 52.5 mm, on the ladder); with no least speed it gets
// the least radius; a fast one over a long link gets the cap.
TEST(ValiditySizerTest, StaysWithinItsBounds) {
  ValiditySizer still;
  Move(still, 0, 0.1, 0);
  still.AddRoundTrip(0.1, 0.3);
  EXPECT_NEAR(still.WantedRadius(), Rung(0.1 * 0.35 * 1.5, 1e-3), 1e-12);
  ValiditySizer unhurried({.least_speed_m_per_s = 0});
  Move(unhurried, 0, 0.1, 0);
  unhurried.AddRoundTrip(0.1, 0.3);
  EXPECT_DOUBLE_EQ(unhurried.WantedRadius(), 1e-3);
  ValiditySizer fast({.max_m = 0.04});
  Move(fast, 0, 0.1, 2.0);
  fast.AddRoundTrip(0.1, 0.3);
  EXPECT_DOUBLE_EQ(fast.WantedRadius(), 0.04);
}

// A stall's round trip is remembered for at least half a window and
// forgotten within a whole one once the link is quick again.
TEST(ValiditySizerTest, RemembersAPeakForAWindowThenForgetsIt) {
  ValiditySizer sizer({.window_s = 1.0});
  Move(sizer, 0, 3.0, 0.1);
  sizer.AddRoundTrip(0.0, 0.05);
  sizer.AddRoundTrip(0.1, 0.4);  // a stall
  for (int k = 2; k <= 30; ++k) {
    const double t = 0.1 * k;
    sizer.AddRoundTrip(t, 0.05);
    if (t <= 0.6) {
      EXPECT_DOUBLE_EQ(sizer.peak_round_trip_s(), 0.4) << t;
    }
    if (t >= 1.1) {
      EXPECT_DOUBLE_EQ(sizer.peak_round_trip_s(), 0.05) << t;
    }
  }
}

// Samples that are not finite, negative round trips and time running
// backward change nothing.
TEST(ValiditySizerTest, IgnoresBadSamples) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  ValiditySizer sizer;
  Move(sizer, 0, 0.1, 0.1);
  sizer.AddRoundTrip(0.1, 0.1);
  const double wanted = sizer.WantedRadius();
  sizer.AddDevicePosition(kNaN, Vector3d::Zero());
  sizer.AddDevicePosition(0.2, Vector3d(kNaN, 0, 0));
  sizer.AddDevicePosition(0.05, Vector3d(5, 0, 0));  // earlier than the last
  sizer.AddRoundTrip(0.2, kNaN);
  sizer.AddRoundTrip(0.2, -1);
  sizer.AddRoundTrip(kNaN, 0.5);
  EXPECT_DOUBLE_EQ(sizer.WantedRadius(), wanted);
  EXPECT_TRUE(std::isfinite(sizer.WantedRadius()));
}

}  // namespace
}  // namespace hs

// What a device's poses ask of the server's model: a fresh one only on the
// first pose after the loop went past its sphere, and the radius the
// sizer wants from the same samples.

#include "client/haptic_loop/model_request.h"

#include <gtest/gtest.h>

namespace hs {
namespace {

// Stale once per new tick past the sphere, not again until the count grows.
TEST(ModelRequesterTest, StaleOnlyWhenTheLoopWentPastItsSphereSinceTheLastPose) {
  ModelRequester requester;
  const Vector3d p = Vector3d::Zero();
  EXPECT_FALSE(requester.ForPose(0.000, p, 0).model_stale);
  EXPECT_TRUE(requester.ForPose(0.004, p, 3).model_stale);
  EXPECT_FALSE(requester.ForPose(0.008, p, 3).model_stale);
  EXPECT_TRUE(requester.ForPose(0.012, p, 4).model_stale);
}

// The radius is the sizer's, fed the same positions and round trips (the
// oracle: a ValiditySizer of its own, fed by hand).
TEST(ModelRequesterTest, RadiusIsTheSizersOverTheSameSamples) {
  const ValiditySizerOptions options{.max_m = 0.04};
  ModelRequester requester(options);
  ValiditySizer sizer(options);
  EXPECT_EQ(requester.ForPose(0, Vector3d::Zero(), 0).validity_radius_m, 0.04);
  sizer.AddDevicePosition(0, Vector3d::Zero());
  for (int k = 1; k <= 50; ++k) {
    const double t = 0.004 * k;
    const Vector3d p(0.05 * t, 0, 0);  // 0.05 m/s
    if (k == 10) {
      requester.AddRoundTrip(t, 0.08);
      sizer.AddRoundTrip(t, 0.08);
    }
    sizer.AddDevicePosition(t, p);
    EXPECT_EQ(requester.ForPose(t, p, 0).validity_radius_m, sizer.WantedRadius()) << k;
  }
  EXPECT_LT(sizer.WantedRadius(), 0.04);  // sized, not the most
}

}  // namespace
}  // namespace hs

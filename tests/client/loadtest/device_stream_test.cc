#include "client/loadtest/device_stream.h"

#include <gtest/gtest.h>

#include "common/api/proto_convert.h"
#include "tests/server/test_server.h"

namespace hs::cli {
namespace {

// The probe's pose in the small test scene.
Isometry3d ProbeStart(const haptics::v1::SceneSpec& spec) {
  return *PoseFromProto(spec.objects(spec.objects_size() - 1).pose(), "probe");
}

// A device attached to the small scene's probe sends its whole path on
// the schedule; every pose is answered once, and its frames and drops
// cover the steps it saw.
TEST(DeviceStreamTest, EveryPoseAnswered) {
  hs::testing::TestServer server;
  const haptics::v1::SceneSpec spec = hs::testing::SmallScene("s");
  server.Create(spec);
  std::atomic<int64_t> frame_bytes{0};
  DeviceStream device(server.sessions(), {.scene = "s", .tool = "probe", .needs = {Effect::kForce}},
                      MotionPath(Motion::kPress, ProbeStart(spec), 200, 0.25), frame_bytes);
  ASSERT_TRUE(device.Attached());
  EXPECT_GT(frame_bytes.load(), 0);
  device.Run({.start = SendSchedule::Clock::now(), .rate_hz = 200}, /*keep_step_times=*/true);
  ASSERT_TRUE(device.status().ok()) << device.status().error_message();
  const StreamReport report = device.Report(1.0);
  EXPECT_EQ(report.sent, 50);
  EXPECT_EQ(report.answered, 50);
  EXPECT_EQ(report.rtt_ms.count, 50);
  EXPECT_EQ(report.frames + report.dropped_frames, report.last_step - report.first_step + 1);
  EXPECT_FALSE(device.step_ms().empty());
}

// A pose message carries its sequence and the path's pose; with every
// pose alike, the mean size is that of any one.
TEST(DeviceStreamTest, Requests) {
  hs::testing::TestServer server;
  std::atomic<int64_t> frame_bytes{0};
  Isometry3d X = Isometry3d::Identity();
  X.translation() = Vector3d(0.1, 0.2, 0.3);
  const std::vector<TimedPose> still(40, TimedPose{.t_s = 0, .X_WD = X});
  DeviceStream device(server.sessions(), {.scene = "none", .tool = "probe"}, still, frame_bytes);
  const haptics::v1::InteractRequest request = device.Request(7);
  EXPECT_EQ(request.pose().sequence(), 7u);
  EXPECT_TRUE(PoseFromProto(request.pose().pose(), "pose")->isApprox(X, 1e-12));
  EXPECT_EQ(device.MeanRequestBytes(), static_cast<int64_t>(request.ByteSizeLong()));
}

// The open message names the scene and tool, and says whether the device
// reads a local model's surface alone (the default, as the SDK's device)
// or its planes too.
TEST(DeviceStreamTest, OpenSaysWhetherTheDeviceReadsPlanes) {
  const haptics::v1::InteractRequest surface =
      OpenRequest({.scene = "s", .tool = "probe", .needs = {Effect::kForce, Effect::kLocalModel}});
  EXPECT_EQ(surface.open().scene(), "s");
  EXPECT_EQ(surface.open().tool(), "probe");
  EXPECT_TRUE(surface.open().surface_only());
  const haptics::v1::InteractRequest planes = OpenRequest(
      {.scene = "s", .tool = "probe", .needs = {Effect::kLocalModel}, .surface_only = false});
  EXPECT_FALSE(planes.open().surface_only());
}

// A tool the scene does not have: the device never attaches, and Finish
// says why.
TEST(DeviceStreamTest, NoSuchTool) {
  hs::testing::TestServer server;
  server.Create(hs::testing::SmallScene("s"));
  std::atomic<int64_t> frame_bytes{0};
  DeviceStream device(server.sessions(), {.scene = "s", .tool = "nothing"}, {}, frame_bytes);
  EXPECT_FALSE(device.Attached());
  EXPECT_FALSE(device.Finish().ok());
}

}  // namespace
}  // namespace hs::cli

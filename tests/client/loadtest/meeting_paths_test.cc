// `loadtest --tools-meet`: the scene puts the tools in pairs, and each
// pair's paths cross at the middle of each press.
#include <gtest/gtest.h>

#include "client/loadtest/loadtest.h"
#include "common/api/proto_convert.h"

namespace hs::cli {
namespace {

Isometry3d At(double x, double y, double z) {
  Isometry3d X = Isometry3d::Identity();
  X.translation() = Vector3d(x, y, z);
  return X;
}

// Four tools from the built-in probe at (0.1, 0, 0.1): pair 0 at angle 0,
// pair 1 turned half a turn, the two of a pair kMeetGapM apart along y.
TEST(MeetingPathsTest, SceneMakesPairs) {
  absl::StatusOr<haptics::v1::SceneSpec> spec =
      LoadtestScene(BuiltInLoadScene(), 4, "meet", /*tools_meet=*/true);
  ASSERT_TRUE(spec.ok()) << spec.status();
  std::vector<Vector3d> at;
  for (int i = 0; i < 4; ++i) {
    const auto& tool = spec->objects(spec->objects_size() - 4 + i);
    EXPECT_EQ(tool.name(), "tool-" + std::to_string(i));
    at.push_back(PoseFromProto(tool.pose(), "pose")->translation());
  }
  EXPECT_TRUE(at[0].isApprox(Vector3d(0.1, -0.5 * kMeetGapM, 0.1), 1e-12));
  EXPECT_TRUE(at[1].isApprox(Vector3d(0.1, 0.5 * kMeetGapM, 0.1), 1e-12));
  EXPECT_TRUE(at[2].isApprox(Vector3d(-0.1, 0.5 * kMeetGapM, 0.1), 1e-12));
  EXPECT_TRUE(at[3].isApprox(Vector3d(-0.1, -0.5 * kMeetGapM, 0.1), 1e-12));
}

// Each device presses towards its partner to kMeetPastM past the middle
// at half a second (the raised cosine's top) and is back at one second;
// the lone third device presses down.
TEST(MeetingPathsTest, PairsCrossAtTheMiddle) {
  const std::vector<Isometry3d> starts = {At(0, -0.03, 0), At(0, 0.03, 0), At(1, 0, 0)};
  const std::vector<std::vector<TimedPose>> paths = MeetingPaths(starts, 1000, 1);
  ASSERT_EQ(paths.size(), 3u);
  for (const auto& path : paths) ASSERT_EQ(path.size(), 1000u);
  // Pairs start in step (phase 0 for pair 0, half a second for pair 1).
  EXPECT_TRUE(paths[0][500].X_WD.translation().isApprox(Vector3d(0, kMeetPastM, 0), 1e-12));
  EXPECT_TRUE(paths[1][500].X_WD.translation().isApprox(Vector3d(0, -kMeetPastM, 0), 1e-12));
  EXPECT_TRUE(paths[0][0].X_WD.isApprox(starts[0], 1e-12));
  EXPECT_TRUE(paths[2][0].X_WD.translation().isApprox(Vector3d(1, 0, -0.02), 1e-12));
  EXPECT_TRUE(paths[2][500].X_WD.translation().isApprox(Vector3d(1, 0, 0), 1e-12));
}

}  // namespace
}  // namespace hs::cli

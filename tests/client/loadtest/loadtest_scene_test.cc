#include "client/loadtest/loadtest_scene.h"

#include <gtest/gtest.h>

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
TEST(LoadtestSceneTest, SceneMakesPairs) {
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
TEST(LoadtestSceneTest, PairsCrossAtTheMiddle) {
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

// Without tools_meet each device presses its own tool from where the scene
// put it, device i a phase of i / clients second later: device 1 of 2 is
// at the top of its press (half a second in) when device 0 starts; with
// tools_meet the paths are MeetingPaths of the same starts.
TEST(LoadtestSceneTest, DevicePathsStartAtTheTools) {
  const absl::StatusOr<haptics::v1::SceneSpec> spec = LoadtestScene(BuiltInLoadScene(), 2, "d");
  ASSERT_TRUE(spec.ok()) << spec.status();
  const absl::StatusOr<std::vector<std::vector<TimedPose>>> paths =
      DevicePaths(*spec, 2, /*tools_meet=*/false, 100, 1);
  ASSERT_TRUE(paths.ok()) << paths.status();
  ASSERT_EQ(paths->size(), 2u);
  std::vector<Isometry3d> starts;
  for (int i = 0; i < 2; ++i) {
    starts.push_back(*PoseFromProto(spec->objects(spec->objects_size() - 2 + i).pose(), "pose"));
    EXPECT_EQ((*paths)[i].size(), 100u);
  }
  EXPECT_TRUE((*paths)[0][0].X_WD.isApprox(starts[0], 1e-12));
  EXPECT_TRUE((*paths)[0][50].X_WD.translation().isApprox(
      starts[0].translation() - Vector3d(0, 0, 0.02), 1e-12));
  EXPECT_TRUE((*paths)[1][0].X_WD.translation().isApprox(
      starts[1].translation() - Vector3d(0, 0, 0.02), 1e-12));
  const absl::StatusOr<std::vector<std::vector<TimedPose>>> meeting =
      DevicePaths(*spec, 2, /*tools_meet=*/true, 100, 1);
  ASSERT_TRUE(meeting.ok());
  const std::vector<std::vector<TimedPose>> expected = MeetingPaths(starts, 100, 1);
  for (int i = 0; i < 2; ++i) {
    for (size_t k = 0; k < expected[i].size(); ++k) {
      EXPECT_TRUE((*meeting)[i][k].X_WD.isApprox(expected[i][k].X_WD, 1e-12)) << i << " " << k;
    }
  }
}

}  // namespace
}  // namespace hs::cli

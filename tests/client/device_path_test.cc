#include "client/device_path.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <string>

#include "tests/common/scratch_dir.h"

namespace hs::cli {
namespace {

constexpr double kPi = std::numbers::pi;

std::string Write(const std::string& name, const std::string& text) {
  const std::string path = (ScratchDir("device_path") / name).string();
  std::ofstream(path) << text;
  return path;
}

// JSON lines: a header naming the scene, then poses with their times, or
// at i / rate where a line gives none; blank lines skipped.
TEST(DevicePathTest, JsonLinesWithTimesAndScene) {
  const std::string path = Write("path.jsonl",
                                 "{\"scene\": \"probe on torus\"}\n"
                                 "{\"t_s\": 0.1, \"pose\": [0.1, 0.2, 0.3, 0, 0, 0]}\n"
                                 "\n"
                                 "{\"pose\": [0, 0, 0, 0, 0, 1.5]}\n"
                                 "{\"t_s\": 0.75, \"pose\": [1, 1, 1, 0, 0, 0]}\n");
  const absl::StatusOr<std::vector<TimedPose>> poses = ReadDevicePath(path, 4);
  ASSERT_TRUE(poses.ok()) << poses.status();
  ASSERT_EQ(poses->size(), 3u);
  EXPECT_EQ((*poses)[0].t_s, 0.1);
  EXPECT_TRUE((*poses)[0].X_WD.translation().isApprox(Vector3d(0.1, 0.2, 0.3)));
  EXPECT_EQ((*poses)[1].t_s, 1.0 / 4);  // pose 1 at 4 Hz
  EXPECT_NEAR(Eigen::AngleAxisd((*poses)[1].X_WD.linear()).angle(), 1.5, 1e-12);
  EXPECT_EQ((*poses)[2].t_s, 0.75);
  const absl::StatusOr<std::string> scene = DevicePathScene(path);
  ASSERT_TRUE(scene.ok());
  EXPECT_EQ(*scene, "probe on torus");
}

// CSV: pose i at i / rate; the scene from a "# scene:" comment line.
TEST(DevicePathTest, CsvAtTheRate) {
  const std::string path = Write("path.csv",
                                 "# scene: demo\n"
                                 "0,0,0.1,0,0,0\n"
                                 "0,0,0.09,0,0,0\n"
                                 "0,0,0.08,0,0,0\n");
  const absl::StatusOr<std::vector<TimedPose>> poses = ReadDevicePath(path, 100);
  ASSERT_TRUE(poses.ok()) << poses.status();
  ASSERT_EQ(poses->size(), 3u);
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_DOUBLE_EQ((*poses)[i].t_s, i / 100.0);
    EXPECT_NEAR((*poses)[i].X_WD.translation().z(), 0.1 - 0.01 * i, 1e-15);
  }
  EXPECT_EQ(*DevicePathScene(path), "demo");
  EXPECT_EQ(*DevicePathScene(Write("plain.csv", "0,0,0,0,0,0\n# scene: late\n")), "");
}

// Malformed lines and times that go back are INVALID_ARGUMENT naming the
// file and line; a missing file is NOT_FOUND.
TEST(DevicePathTest, BadPathsAreRefused) {
  const std::pair<const char*, const char*> bad[] = {
      {"not json\n", ":1:"},
      {"{\"pose\": [1, 2, 3]}\n", ":1:"},
      {"{\"pose\": [0,0,0,0,0,0]}\n{\"pose\": [0,0,0,0,0,\"x\"]}\n", ":2:"},
      {"{\"t_s\": 1, \"pose\": [0,0,0,0,0,0]}\n{\"t_s\": 0.5, \"pose\": [0,0,0,0,0,0]}\n", ":2:"},
      {"{\"t_s\": \"soon\", \"pose\": [0,0,0,0,0,0]}\n", ":1:"},
  };
  int k = 0;
  for (const auto& [text, line] : bad) {
    const std::string path = Write("bad" + std::to_string(k++) + ".jsonl", text);
    const absl::StatusOr<std::vector<TimedPose>> poses = ReadDevicePath(path, 10);
    EXPECT_EQ(poses.status().code(), absl::StatusCode::kInvalidArgument) << text;
    EXPECT_NE(poses.status().message().find(path + line), std::string::npos) << poses.status();
  }
  const std::string missing = (ScratchDir("device_path_missing") / "none.jsonl").string();
  EXPECT_EQ(ReadDevicePath(missing, 10).status().code(), absl::StatusCode::kNotFound);
  EXPECT_EQ(DevicePathScene(missing).status().code(), absl::StatusCode::kNotFound);
}

// The motions by name; any other name is INVALID_ARGUMENT.
TEST(DevicePathTest, MotionNames) {
  EXPECT_EQ(*ParseMotion("press"), Motion::kPress);
  EXPECT_EQ(*ParseMotion("sweep"), Motion::kSweep);
  EXPECT_EQ(ParseMotion("Press").status().code(), absl::StatusCode::kInvalidArgument);
}

// A press goes down along its direction by the depth and back once a
// second (a raised cosine); a sweep goes down over 0.25 s, then side to
// side by the amplitude every 2 s. Hand-computed points of each.
TEST(DevicePathTest, MotionOffsets) {
  const MotionParams params{.depth_m = 0.02, .amplitude_m = 0.05};
  EXPECT_TRUE(MotionOffset(Motion::kPress, 0, params).isZero());
  EXPECT_TRUE(MotionOffset(Motion::kPress, 0.5, params).isApprox(Vector3d(0, 0, -0.02)));
  EXPECT_TRUE(MotionOffset(Motion::kPress, 0.25, params).isApprox(Vector3d(0, 0, -0.01)));
  EXPECT_NEAR(MotionOffset(Motion::kPress, 1, params).norm(), 0, 1e-15);
  MotionParams sideways = params;
  sideways.press_direction = Vector3d::UnitX();
  EXPECT_TRUE(MotionOffset(Motion::kPress, 0.5, sideways).isApprox(Vector3d(0.02, 0, 0)));
  EXPECT_TRUE(MotionOffset(Motion::kSweep, 0.125, params)
                  .isApprox(Vector3d(0.05 * std::sin(kPi / 8), 0, -0.01)));
  EXPECT_TRUE(MotionOffset(Motion::kSweep, 0.5, params).isApprox(Vector3d(0.05, 0, -0.02)));
  EXPECT_TRUE(MotionOffset(Motion::kSweep, 1.5, params).isApprox(Vector3d(-0.05, 0, -0.02)));
  MotionParams later = params;
  later.phase_s = 0.25;
  EXPECT_TRUE(MotionOffset(Motion::kPress, 0.25, later)
                  .isApprox(MotionOffset(Motion::kPress, 0.5, params)));
}

// A motion path samples the offsets from the start at the rate, keeping the
// start's orientation.
TEST(DevicePathTest, MotionPathSamplesFromTheStart) {
  Isometry3d start = Isometry3d::Identity();
  start.rotate(Eigen::AngleAxisd(0.4, Vector3d::UnitY()));
  start.translation() = Vector3d(0.1, 0, 0.2);
  const std::vector<TimedPose> path = MotionPath(Motion::kSweep, start, 1000, 0.5);
  ASSERT_EQ(path.size(), 500u);
  for (size_t i = 0; i < path.size(); i += 37) {
    EXPECT_DOUBLE_EQ(path[i].t_s, i / 1000.0);
    EXPECT_TRUE(path[i].X_WD.linear().isApprox(start.linear()));
    const Vector3d offset = path[i].X_WD.translation() - start.translation();
    EXPECT_LT((offset - MotionOffset(Motion::kSweep, path[i].t_s, {})).norm(), 1e-15) << i;
  }
}

}  // namespace
}  // namespace hs::cli

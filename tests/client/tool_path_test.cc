#include "client/tool_path.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <random>
#include <string>

#include "client/pose_args.h"
#include "tests/common/scratch_dir.h"

namespace hs::cli {
namespace {

using ::testing::HasSubstr;

std::string WriteFile(const std::string& name, const std::string& text) {
  const std::string path = (ScratchDir("tool_path") / name).string();
  std::ofstream(path) << text;
  return path;
}

// Poses written at full precision read back as the poses PoseFromNumbers
// builds from the same numbers, in file order, with comments and blank
// lines (spaces, tabs, CRLF) skipped.
TEST(ToolPathTest, ReadsEveryPoseInOrder) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-1, 1);
  std::string text = "# a path\n\n";
  std::vector<Isometry3d> expected;
  for (int i = 0; i < 50; ++i) {
    const Vector3d p(u(rng), u(rng), u(rng));
    const Vector3d r = 3 * Vector3d(u(rng), u(rng), u(rng));
    char line[256];
    std::snprintf(line, sizeof line, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g", p.x(), p.y(), p.z(),
                  r.x(), r.y(), r.z());
    text += line;
    text += i % 3 == 0 ? "  # trailing comment\n" : (i % 3 == 1 ? "\r\n" : "\n");
    if (i % 10 == 0) text += " \t\r\n";
    expected.push_back(PoseFromNumbers(p, r));
  }
  const absl::StatusOr<std::vector<Isometry3d>> poses = ReadToolPath(WriteFile("ok.csv", text));
  ASSERT_TRUE(poses.ok()) << poses.status();
  ASSERT_EQ(poses->size(), expected.size());
  for (size_t i = 0; i < expected.size(); ++i) {
    EXPECT_TRUE(poses->at(i).isApprox(expected[i], 0.0)) << "pose " << i;
  }
}

// A bad line is reported with the file and its line number; nothing is
// returned for the lines before it.
TEST(ToolPathTest, BadLineNamesFileAndLine) {
  const std::string path = WriteFile("bad.csv", "0,0,0,0,0,0\n# comment\n1,2,3\n");
  const absl::StatusOr<std::vector<Isometry3d>> poses = ReadToolPath(path);
  ASSERT_EQ(poses.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(poses.status().message(), HasSubstr(path + ":3:"));
  const absl::StatusOr<std::vector<Isometry3d>> nan =
      ReadToolPath(WriteFile("nan.csv", "0,0,nan,0,0,0\n"));
  EXPECT_EQ(nan.status().code(), absl::StatusCode::kInvalidArgument);
}

// No path means no poses; a path that cannot be opened is NOT_FOUND.
TEST(ToolPathTest, EmptyAndMissingPaths) {
  const absl::StatusOr<std::vector<Isometry3d>> none = ReadToolPath("");
  ASSERT_TRUE(none.ok());
  EXPECT_TRUE(none->empty());
  EXPECT_EQ(ReadToolPath((ScratchDir("missing") / "no_such.csv").string()).status().code(),
            absl::StatusCode::kNotFound);
}

}  // namespace
}  // namespace hs::cli

#include "client/inspect_command.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "client/exit_codes.h"
#include "tests/common/scratch_dir.h"

namespace hs::cli {
namespace {

// Writes a closed tetrahedron as OBJ into a scratch folder of this process.
std::string WriteTetrahedron() {
  const std::filesystem::path path = ScratchDir("inspect") / "tetra.obj";
  std::ofstream(path) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                         "f 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n";
  return path.string();
}

// The JSON summary carries the counts and the closedness the HDS computes.
TEST(InspectCommandTest, JsonSummaryOfTetrahedron) {
  std::ostringstream out, err;
  InspectArgs args{.file = WriteTetrahedron(), .json = true};
  ASSERT_EQ(RunInspect(args, out, err), kExitOk) << err.str();
  const auto j = nlohmann::json::parse(out.str());
  EXPECT_EQ(j["vertices"], 4);
  EXPECT_EQ(j["edges"], 6);
  EXPECT_EQ(j["faces"], 4);
  EXPECT_EQ(j["closed"], true);
  EXPECT_EQ(j["euler_characteristic"], 2);
  EXPECT_EQ(j["bounding_box_m"]["max"][2], 1.0);
  EXPECT_EQ(j["materials"].size(), 1u);
}

// --unit-scale scales the bounding box the summary reports.
TEST(InspectCommandTest, UnitScaleScalesBox) {
  std::ostringstream out, err;
  InspectArgs args{.file = WriteTetrahedron(), .unit_scale = 0.001, .json = true};
  ASSERT_EQ(RunInspect(args, out, err), kExitOk) << err.str();
  EXPECT_DOUBLE_EQ(nlohmann::json::parse(out.str())["smallest_box_edge_m"].get<double>(), 0.001);
}

// The text form prints one "key: value" line per field.
TEST(InspectCommandTest, TextSummary) {
  std::ostringstream out, err;
  ASSERT_EQ(RunInspect(InspectArgs{.file = WriteTetrahedron()}, out, err), kExitOk);
  EXPECT_NE(out.str().find("faces: 4\n"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("closed: true\n"), std::string::npos) << out.str();
}

// A missing file fails with the file named on the error stream and nothing on out.
TEST(InspectCommandTest, MissingFileFails) {
  std::ostringstream out, err;
  EXPECT_EQ(RunInspect(InspectArgs{.file = "/nonexistent/model.obj"}, out, err), kExitFailure);
  EXPECT_NE(err.str().find("/nonexistent/model.obj"), std::string::npos) << err.str();
  EXPECT_TRUE(out.str().empty());
}

}  // namespace
}  // namespace hs::cli

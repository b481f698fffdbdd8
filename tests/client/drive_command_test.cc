#include "client/drive_command.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sstream>

#include "client/exit_codes.h"
#include "server/scene_file.h"
#include "tests/server/test_server.h"

namespace hs::cli {
namespace {

const std::string kScenes = std::string(HS_TEST_DATA_DIR) + "/../../scenes";

// Driving the demo path into a server's demo scene prints frames in pose
// order, ending with the path's last pose, with contacts on the organ.
TEST(DriveCommandTest, DemoPathPrintsContactFrames) {
  testing::TestServer server;
  absl::StatusOr<haptics::v1::SceneSpec> spec =
      ReadSceneFile(kScenes + "/probe_on_torus.textproto");
  ASSERT_TRUE(spec.ok());
  ASSERT_TRUE(server.server().registry().Create(*spec, kScenes).ok());
  DriveArgs args{.server = server.address(),
                 .scene = spec->name(),
                 .tool = "probe",
                 .path = kScenes + "/press_and_slide.csv",
                 .rate_hz = 200,
                 .json = true};
  std::ostringstream out, err;
  ASSERT_EQ(RunDrive(args, out, err), kExitOk) << err.str();
  std::istringstream lines(out.str());
  int64_t last_sequence = 0;
  int touching = 0;
  for (std::string line; std::getline(lines, line);) {
    const nlohmann::json frame = nlohmann::json::parse(line);
    const int64_t sequence = std::stoll(frame.at("last_pose_sequence").get<std::string>());
    EXPECT_GT(sequence, last_sequence);
    last_sequence = sequence;
    for (const auto& contact : frame["tools"][0].value("contacts", nlohmann::json::array())) {
      touching += contact.at("object") == "organ";
    }
  }
  EXPECT_EQ(last_sequence, 60);
  EXPECT_GT(touching, 10);
}

// An unknown scene fails with the server's status on stderr.
TEST(DriveCommandTest, UnknownSceneFails) {
  testing::TestServer server;
  DriveArgs args{.server = server.address(),
                 .scene = "nowhere",
                 .tool = "probe",
                 .path = kScenes + "/press_and_slide.csv",
                 .rate_hz = 1000,
                 .json = false};
  std::ostringstream out, err;
  EXPECT_EQ(RunDrive(args, out, err), kExitFailure);
  EXPECT_NE(err.str().find("NOT_FOUND"), std::string::npos) << err.str();
}

}  // namespace
}  // namespace hs::cli

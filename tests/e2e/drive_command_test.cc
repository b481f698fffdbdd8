#include "client/drive_command.h"

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "client/exit_codes.h"
#include "tests/common/scratch_dir.h"
#include "tests/server/test_server.h"

namespace hs::cli {
namespace {

class DriveCommandTest : public ::testing::Test {
 protected:
  DriveCommandTest() {
    server_.Create(hs::testing::SmallScene("s"));
    args_.server.address = server_.address();
    args_.scene = "s";
    args_.tool = "probe";
    args_.rate_hz = 500;
  }

  hs::testing::TestServer server_;
  DriveArgs args_;
  std::ostringstream out_, err_;
};

// A press motion from the probe's pose 5 cm above the table, 6 cm deep,
// reaches the table: the last frames report contact, and the last pose
// applied is the last one sent.
TEST_F(DriveCommandTest, PressMotionTouches) {
  args_.motion = "press";
  args_.duration_s = 0.5;
  args_.depth_m = 0.06;
  args_.json = true;
  ASSERT_EQ(RunDrive(args_, out_, err_), kExitOk) << err_.str();
  std::istringstream lines(out_.str());
  std::string line;
  bool touched = false;
  uint64_t last_sequence = 0;
  while (std::getline(lines, line)) {
    const nlohmann::json frame = nlohmann::json::parse(line);
    last_sequence = std::stoull(frame["last_pose_sequence"].get<std::string>());
    touched |= frame["tools"][0].contains("contacts");
  }
  EXPECT_TRUE(touched);
  EXPECT_EQ(last_sequence, 250u);
}

// A JSON-lines path with times plays every pose; a bad line fails before
// anything is sent.
TEST_F(DriveCommandTest, JsonLinesPath) {
  const std::string path = (ScratchDir("drive") / "path.jsonl").string();
  std::ofstream(path) << "{\"t_s\": 0, \"pose\": [0, 0, 0.05, 0, 0, 0]}\n"
                      << "{\"t_s\": 0.01, \"pose\": [0, 0, 0.04, 0, 0, 0]}\n"
                      << "{\"t_s\": 0.02, \"pose\": [0, 0, 0.03, 0, 0, 0]}\n";
  args_.path = path;
  ASSERT_EQ(RunDrive(args_, out_, err_), kExitOk) << err_.str();
  EXPECT_NE(out_.str().find(" pose 3 "), std::string::npos) << out_.str();
  std::ofstream(path) << "{\"t_s\": 0, \"pose\": [0, 0, 0.05]}\n";
  EXPECT_EQ(RunDrive(args_, out_, err_), kExitFailure);
  EXPECT_NE(err_.str().find(":1: "), std::string::npos) << err_.str();
}

// An unknown tool is NOT_FOUND, a held tool is refused (FAILED_PRECONDITION),
// an unreachable server UNAVAILABLE.
TEST_F(DriveCommandTest, ExitStatusesOfFailures) {
  args_.motion = "sweep";
  args_.duration_s = 0.1;
  args_.tool = "nope";
  EXPECT_EQ(RunDrive(args_, out_, err_), kExitNotFound);
  args_.tool = "probe";
  auto context = hs::testing::ContextWithin(30);
  auto holder = server_.sessions().Interact(context.get());
  haptics::v1::InteractRequest open;
  open.mutable_open()->set_scene("s");
  open.mutable_open()->set_tool("probe");
  holder->Write(open);
  haptics::v1::Frame frame;
  ASSERT_TRUE(holder->Read(&frame));
  EXPECT_EQ(RunDrive(args_, out_, err_), kExitRefused);
  EXPECT_NE(err_.str().find("FAILED_PRECONDITION: "), std::string::npos) << err_.str();
  context->TryCancel();
  args_.server.address = "127.0.0.1:1";
  EXPECT_EQ(RunDrive(args_, out_, err_), kExitUnavailable);
}

}  // namespace
}  // namespace hs::cli

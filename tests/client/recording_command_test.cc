// `hapticctl recording` on a session recorded without a server
// (tests/common/recording/recorded_run.h); its errors are in
// replay_command_test.

#include "client/recording_command.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>

#include "client/exit_codes.h"
#include "tests/common/recording/recorded_run.h"
#include "tests/common/scratch_dir.h"

namespace hs::cli {
namespace {

namespace pb = haptics::v1;

std::string RecordedFile(const std::string& name, int steps) {
  return testing_recording::WriteRecords((ScratchDir("recording_command") / name).string(),
                                         testing_recording::RecordRun({.steps = steps}));
}

// --json prints one object with the summary's figures and the files.
TEST(RecordingCommandTest, JsonSummary) {
  const std::string file = RecordedFile("run.hsrec", 5);
  std::ostringstream out, err;
  ASSERT_EQ(RunRecording({.file = file, .json = true}, out, err), kExitOk) << err.str();
  const nlohmann::json j = nlohmann::json::parse(out.str());
  EXPECT_EQ(j["scene"], "press");
  EXPECT_EQ(j["start_unix_ns"], testing_recording::kStartUnixNs);
  EXPECT_EQ(j["frames"], "full");
  EXPECT_EQ(j["first_step"], 1);
  EXPECT_EQ(j["last_step"], 5);
  EXPECT_EQ(j["steps"], 5);
  EXPECT_EQ(j["inputs"], 5);
  EXPECT_EQ(j["edits"], 0);
  EXPECT_EQ(j["ended"], true);
  ASSERT_EQ(j["files"].size(), 1u);
  EXPECT_EQ(j["files"][0]["path"], file);
  EXPECT_EQ(j["files"][0]["part"], 0);
  EXPECT_EQ(j["files"][0]["bytes"], std::filesystem::file_size(file));
  EXPECT_EQ(j["files"][0]["torn"], false);
}

// Text: one "key: value" line per figure, the files by index.
TEST(RecordingCommandTest, TextSummary) {
  const std::string file = RecordedFile("text.hsrec", 3);
  std::ostringstream out, err;
  ASSERT_EQ(RunRecording({.file = file, .json = false}, out, err), kExitOk) << err.str();
  EXPECT_NE(out.str().find("scene: press\n"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("steps: 3\n"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("files[0].path: " + file + "\n"), std::string::npos) << out.str();
}

// A torn file's entry says where it was cut and why.
TEST(RecordingCommandTest, FilesJsonNamesATornTail) {
  const std::vector<SessionFile> files = {
      {.path = "a.hsrec", .part = 0, .bytes = 100, .whole_bytes = 100, .torn_reason = ""},
      {.path = "b.hsrec", .part = 1, .bytes = 90, .whole_bytes = 70, .torn_reason = "cut short"}};
  const nlohmann::ordered_json j = FilesJson(files);
  EXPECT_EQ(j[0].dump(), R"({"path":"a.hsrec","part":0,"bytes":100,"torn":false})");
  EXPECT_EQ(j[1].dump(), R"({"path":"b.hsrec","part":1,"bytes":90,"torn":true,"cut_at_byte":70,)"
                         R"("torn_bytes":20,"torn_reason":"cut short"})");
}

}  // namespace
}  // namespace hs::cli

// `hapticctl recording` and `replay` on files that are not whole
// recordings: a clear error and a non-zero exit, never a crash or a hang.

#include "client/replay_command.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "client/exit_codes.h"
#include "client/recording_command.h"
#include "common/recording/record_file.h"
#include "tests/common/scratch_dir.h"

namespace hs::cli {
namespace {

std::string Write(const std::string& name, const std::string& bytes) {
  const std::string path = (ScratchDir("replay_command") / name).string();
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

// Both commands, on `path`: the exit code of each and what they said.
void ExpectRefused(const std::string& path, const std::string& says) {
  std::ostringstream out, err;
  EXPECT_EQ(RunRecording({.file = path, .json = false}, out, err), kExitFailure) << path;
  EXPECT_NE(err.str().find(says), std::string::npos) << err.str();
  std::ostringstream replay_out, replay_err;
  EXPECT_EQ(RunReplay({.file = path, .model_dir = "", .json = false}, replay_out, replay_err),
            kExitFailure)
      << path;
  EXPECT_NE(replay_err.str().find(says), std::string::npos) << replay_err.str();
}

TEST(ReplayCommandTest, FilesThatAreNotRecordingsAreRefused) {
  ExpectRefused(Write("foreign.hsrec", "solid cube\nfacet normal 0 0 1\n"), "is not a recording");
  ExpectRefused(Write("empty.hsrec", ""), "is not a recording");
  ExpectRefused((ScratchDir("replay_command") / "missing.hsrec").string(), "no recording file");
  // The magic, then a torn first record: no session start to begin from.
  ExpectRefused(Write("torn.hsrec", std::string(kRecordingMagic, kRecordingMagicBytes) + "\x05\0"),
                "no session start");
  // Whole records, but the first is not the session's start.
  const std::string path = (ScratchDir("replay_command") / "headless.hsrec").string();
  {
    absl::StatusOr<RecordFileWriter> writer = RecordFileWriter::Create(path);
    ASSERT_TRUE(writer.ok());
    haptics::v1::Record frame;
    frame.mutable_frame()->set_step(1);
    ASSERT_TRUE(writer->Append(frame).ok());
  }
  ExpectRefused(path, "no session start");
}

// A session whose scene no longer builds (its uploaded model is gone)
// names the cause.
TEST(ReplayCommandTest, SceneThatDoesNotBuildIsNamed) {
  const std::string path = (ScratchDir("replay_command") / "lost_model.hsrec").string();
  {
    absl::StatusOr<RecordFileWriter> writer = RecordFileWriter::Create(path);
    ASSERT_TRUE(writer.ok());
    haptics::v1::Record start;
    start.mutable_start()->set_scene("lost");
    start.mutable_start()->set_step_s(0.001);
    start.mutable_start()->set_uploaded_models_dir(ScratchDir("no_models").string());
    haptics::v1::SceneObject* o = start.mutable_start()->mutable_spec()->add_objects();
    o->set_name("gone");
    o->set_kind(haptics::v1::OBJECT_KIND_FIXED);
    o->mutable_model()->set_uploaded_model_id("gone.obj");
    start.mutable_start()->mutable_spec()->set_name("lost");
    ASSERT_TRUE(writer->Append(start).ok());
  }
  std::ostringstream out, err;
  EXPECT_EQ(RunReplay({.file = path, .model_dir = "", .json = false}, out, err), kExitFailure);
  EXPECT_NE(err.str().find("gone.obj"), std::string::npos) << err.str();
  std::ostringstream summary, summary_err;
  EXPECT_EQ(RunRecording({.file = path, .json = false}, summary, summary_err), kExitOk);
  EXPECT_NE(summary.str().find("steps: 0"), std::string::npos) << summary.str();
}

}  // namespace
}  // namespace hs::cli

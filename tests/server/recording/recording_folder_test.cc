#include "server/recording/recording_folder.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/recording/record_file.h"
#include "tests/common/scratch_dir.h"

namespace hs {
namespace {

// A recording of `records` frames, whole.
void WriteRecording(const std::filesystem::path& path, int records) {
  absl::StatusOr<RecordFileWriter> writer = RecordFileWriter::Create(path.string());
  ASSERT_TRUE(writer.ok()) << writer.status();
  haptics::v1::Record record;
  for (int i = 1; i <= records; ++i) {
    record.mutable_frame()->set_step(i);
    ASSERT_TRUE(writer->Append(record).ok());
  }
}

// A missing folder is made, with its parents.
TEST(RecordingFolderTest, MakesTheFolder) {
  const std::filesystem::path dir = ScratchDir("recording_folder_new") / "a" / "b";
  ASSERT_TRUE(PrepareRecordingFolder(dir.string()).ok());
  EXPECT_TRUE(std::filesystem::is_directory(dir));
  ASSERT_TRUE(PrepareRecordingFolder(dir.string()).ok());  // and again: nothing to do
}

// A recording a crash tore is cut back to its whole records, saying so; a
// whole one, a file of another kind and a .hsrec that is no recording are
// left as they are (the last named as such).
TEST(RecordingFolderTest, CutsTornRecordingsOnly) {
  const std::filesystem::path dir = ScratchDir("recording_folder_torn");
  WriteRecording(dir / "whole.hsrec", 3);
  WriteRecording(dir / "torn.hsrec", 3);
  const auto whole_size = std::filesystem::file_size(dir / "torn.hsrec");
  std::ofstream(dir / "torn.hsrec", std::ios::binary | std::ios::app) << std::string("\x40\0\0", 3);
  std::ofstream(dir / "notes.txt", std::ios::binary) << "ends mid-line";
  std::ofstream(dir / "foreign.hsrec", std::ios::binary) << "not a recording at all";
  testing::internal::CaptureStderr();
  ASSERT_TRUE(PrepareRecordingFolder(dir.string()).ok());
  const std::string said = testing::internal::GetCapturedStderr();
  EXPECT_EQ(std::filesystem::file_size(dir / "torn.hsrec"), whole_size);
  EXPECT_EQ(std::filesystem::file_size(dir / "whole.hsrec"), whole_size);
  EXPECT_EQ(std::filesystem::file_size(dir / "notes.txt"), 13u);
  EXPECT_EQ(std::filesystem::file_size(dir / "foreign.hsrec"), 22u);
  EXPECT_NE(
      said.find((dir / "torn.hsrec").string() + " was cut short by a crash: its torn last 3 bytes"),
      std::string::npos)
      << said;
  EXPECT_NE(said.find((dir / "foreign.hsrec").string() + " left as it is"), std::string::npos)
      << said;
  EXPECT_EQ(said.find("whole.hsrec"), std::string::npos) << said;
  EXPECT_EQ(said.find("notes.txt"), std::string::npos) << said;
  const absl::StatusOr<RecordFileContents> cut = ReadRecordFile((dir / "torn.hsrec").string());
  ASSERT_TRUE(cut.ok());
  EXPECT_EQ(cut->records.size(), 3u);
  EXPECT_FALSE(cut->torn());
}

// A folder that cannot be made (a file is in the way) is UNAVAILABLE
// naming it.
TEST(RecordingFolderTest, UnmakeableFolderIsUnavailable) {
  const std::filesystem::path dir = ScratchDir("recording_folder_blocked");
  std::ofstream(dir / "file") << "x";
  const std::string wanted = (dir / "file" / "recordings").string();
  const absl::Status status = PrepareRecordingFolder(wanted);
  EXPECT_EQ(status.code(), absl::StatusCode::kUnavailable);
  EXPECT_NE(status.message().find(wanted), std::string::npos) << status;
}

}  // namespace
}  // namespace hs

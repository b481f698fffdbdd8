#include "common/recording/session_reader.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <vector>

#include "common/recording/record_file.h"
#include "common/recording/session_files.h"
#include "google/protobuf/util/message_differencer.h"
#include "tests/common/recording/recorded_run.h"
#include "tests/common/scratch_dir.h"

namespace hs {
namespace {

namespace pb = haptics::v1;
using google::protobuf::util::MessageDifferencer;
using testing_recording::kStartUnixNs;
using testing_recording::RecordRun;
using testing_recording::WriteRecords;

// Writes `records` as a session in `dir`, a new part (its own start, part
// number counting up) beginning at each index in `part_starts`. Returns the
// parts' paths and the records as they are in the files.
std::vector<std::string> WriteParts(const std::filesystem::path& dir,
                                    std::vector<pb::Record> records,
                                    const std::vector<size_t>& part_starts,
                                    std::vector<pb::Record>& written) {
  std::vector<std::string> paths;
  std::vector<pb::Record> part = {records[0]};
  auto flush = [&] {
    const std::string path =
        (dir / SessionFileName("press", kStartUnixNs, static_cast<int>(paths.size()))).string();
    paths.push_back(WriteRecords(path, part));
    written.insert(written.end(), part.begin(), part.end());
  };
  for (size_t i = 1; i < records.size(); ++i) {
    if (std::find(part_starts.begin(), part_starts.end(), i) != part_starts.end()) {
      flush();
      part = {records[0]};
      part[0].mutable_start()->set_part(static_cast<int>(paths.size()));
    }
    part.push_back(records[i]);
  }
  flush();
  return paths;
}

void ExpectSameRecords(const std::vector<pb::Record>& got, const std::vector<pb::Record>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (size_t i = 0; i < got.size(); ++i) {
    EXPECT_TRUE(MessageDifferencer::Equals(got[i], want[i])) << i;
  }
}

// A session in three parts reads back whole: every record in order, each
// file with its part number and size.
TEST(SessionReaderTest, PartsReadBackInOrder) {
  const std::filesystem::path dir = ScratchDir("session_reader_parts");
  std::vector<pb::Record> written;
  const std::vector<std::string> paths = WriteParts(dir, RecordRun({.steps = 6}), {5, 9}, written);
  const absl::StatusOr<RecordedSession> session = ReadSession(paths[0]);
  ASSERT_TRUE(session.ok()) << session.status();
  ExpectSameRecords(session->records, written);
  ASSERT_EQ(session->files.size(), 3u);
  for (int part = 0; part < 3; ++part) {
    const SessionFile& file = session->files[part];
    EXPECT_EQ(file.path, paths[part]);
    EXPECT_EQ(file.part, part);
    EXPECT_EQ(file.bytes, static_cast<int64_t>(std::filesystem::file_size(paths[part])));
    EXPECT_EQ(file.whole_bytes, file.bytes);
    EXPECT_EQ(file.torn_reason, "");
  }
  // From a later part on: that part and the ones after it.
  const absl::StatusOr<RecordedSession> later = ReadSession(paths[1]);
  ASSERT_TRUE(later.ok()) << later.status();
  EXPECT_EQ(later->files.size(), 2u);
}

// A crash cut the second part: reading stops at its last whole record,
// says why, and reads no part after it.
TEST(SessionReaderTest, TornPartEndsTheSession) {
  const std::filesystem::path dir = ScratchDir("session_reader_torn");
  std::vector<pb::Record> written;
  const std::vector<std::string> paths = WriteParts(dir, RecordRun({.steps = 6}), {5, 9}, written);
  const auto size = std::filesystem::file_size(paths[1]);
  std::filesystem::resize_file(paths[1], size - 3);
  const absl::StatusOr<RecordedSession> session = ReadSession(paths[0]);
  ASSERT_TRUE(session.ok()) << session.status();
  ASSERT_EQ(session->files.size(), 2u);
  EXPECT_NE(session->files[1].torn_reason, "");
  EXPECT_LT(session->files[1].whole_bytes, session->files[1].bytes);
  // Part 1 held its start and records 5..8; its last is lost.
  written.resize(5 + 4);
  ExpectSameRecords(session->records, written);
}

// A part cut before its start was written is where the session ends; the
// first file without a start is no session at all.
TEST(SessionReaderTest, PartWithoutStart) {
  const std::filesystem::path dir = ScratchDir("session_reader_headless");
  std::vector<pb::Record> written;
  const std::vector<std::string> paths = WriteParts(dir, RecordRun({.steps = 4}), {5}, written);
  std::ofstream(paths[1], std::ios::binary | std::ios::trunc)
      << std::string(kRecordingMagic, kRecordingMagicBytes);
  const absl::StatusOr<RecordedSession> session = ReadSession(paths[0]);
  ASSERT_TRUE(session.ok()) << session.status();
  EXPECT_EQ(session->files.size(), 1u);
  const absl::StatusOr<RecordedSession> headless = ReadSession(paths[1]);
  EXPECT_EQ(headless.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(headless.status().message().find("no session start"), std::string::npos)
      << headless.status();
}

// A part numbered out of turn, a file that is no recording and a missing
// file are errors naming the cause.
TEST(SessionReaderTest, BadSessionsAreRefused) {
  const std::filesystem::path dir = ScratchDir("session_reader_bad");
  std::vector<pb::Record> written;
  std::vector<pb::Record> records = RecordRun({.steps = 4});
  const std::vector<std::string> paths = WriteParts(dir, records, {5}, written);
  std::vector<pb::Record> skipped = {records[0]};
  skipped[0].mutable_start()->set_part(3);
  std::filesystem::remove(paths[1]);
  WriteRecords(paths[1], skipped);
  absl::StatusOr<RecordedSession> session = ReadSession(paths[0]);
  EXPECT_EQ(session.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(session.status().message().find("part 3 after part 0"), std::string::npos)
      << session.status();

  const std::string text = (dir / "notes.hsrec").string();
  std::ofstream(text) << "not a recording";
  EXPECT_EQ(ReadSession(text).status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(ReadSession((dir / "none.hsrec").string()).status().code(),
            absl::StatusCode::kNotFound);
}

}  // namespace
}  // namespace hs

#include "common/recording/record_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "google/protobuf/util/message_differencer.h"
#include "tests/common/scratch_dir.h"

namespace hs {
namespace {

namespace pb = haptics::v1;

// Records of every kind, of different sizes.
std::vector<pb::Record> SomeRecords() {
  std::vector<pb::Record> records(4);
  records[0].mutable_start()->set_scene("demo");
  records[0].mutable_start()->set_step_s(0.001);
  records[1].mutable_input()->set_step(1);
  records[1].mutable_input()->set_tool("probe");
  for (int i = 0; i < 9; ++i)
    records[1].mutable_input()->mutable_device_pose()->add_rotation_row_major(i);
  records[2].mutable_frame()->set_step(1);
  records[2].mutable_frame()->mutable_frame()->set_time_s(0.001);
  records[3].mutable_end()->set_last_step(1);
  return records;
}

std::string WriteRecords(const std::string& name, const std::vector<pb::Record>& records) {
  const std::string path = (ScratchDir("records") / name).string();
  absl::StatusOr<RecordFileWriter> writer = RecordFileWriter::Create(path);
  EXPECT_TRUE(writer.ok()) << writer.status();
  for (const pb::Record& r : records) EXPECT_TRUE(writer->Append(r).ok());
  EXPECT_TRUE(writer->Sync().ok());
  EXPECT_EQ(writer->bytes(), static_cast<int64_t>(std::filesystem::file_size(path)));
  return path;
}

std::string Bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream all;
  all << in.rdbuf();
  return all.str();
}

void Overwrite(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

TEST(RecordFileTest, RecordsReadBackAsWritten) {
  const std::vector<pb::Record> records = SomeRecords();
  const std::string path = WriteRecords("whole.hsrec", records);
  absl::StatusOr<RecordFileContents> read = ReadRecordFile(path);
  ASSERT_TRUE(read.ok()) << read.status();
  EXPECT_FALSE(read->torn());
  EXPECT_EQ(read->whole_bytes, read->file_bytes);
  ASSERT_EQ(read->records.size(), records.size());
  for (size_t i = 0; i < records.size(); ++i) {
    EXPECT_TRUE(google::protobuf::util::MessageDifferencer::Equals(read->records[i], records[i]));
  }
  // A file may not be written over: a new session never takes an old file.
  EXPECT_FALSE(RecordFileWriter::Create(path).ok());
}

// Cut at every byte, the file reads back as the records that end at or
// before the cut, torn exactly when the cut is inside a record; CutTornTail
// then leaves those records and nothing else.
TEST(RecordFileTest, EveryCutKeepsTheWholeRecordsBeforeIt) {
  const std::vector<pb::Record> records = SomeRecords();
  const std::string whole = Bytes(WriteRecords("cut_source.hsrec", records));
  // Where each record ends, from the lengths in the file.
  std::vector<size_t> ends;
  for (size_t at = kRecordingMagicBytes; at < whole.size();) {
    uint32_t size = 0;
    for (int i = 0; i < 4; ++i) size |= uint32_t{static_cast<uint8_t>(whole[at + i])} << (8 * i);
    at += 8 + size;
    ends.push_back(at);
  }
  ASSERT_EQ(ends.size(), records.size());
  ASSERT_EQ(ends.back(), whole.size());
  const std::string path = (ScratchDir("records") / "cut.hsrec").string();
  for (size_t cut = kRecordingMagicBytes; cut <= whole.size(); ++cut) {
    Overwrite(path, whole.substr(0, cut));
    absl::StatusOr<RecordFileContents> read = ReadRecordFile(path);
    ASSERT_TRUE(read.ok()) << cut;
    size_t expected = 0, expected_bytes = kRecordingMagicBytes;
    while (expected < ends.size() && ends[expected] <= cut) expected_bytes = ends[expected++];
    EXPECT_EQ(read->records.size(), expected) << cut;
    EXPECT_EQ(read->whole_bytes, static_cast<int64_t>(expected_bytes)) << cut;
    EXPECT_EQ(read->torn(), expected_bytes != cut) << cut;
    absl::StatusOr<int64_t> removed = CutTornTail(path);
    ASSERT_TRUE(removed.ok()) << cut;
    EXPECT_EQ(*removed, static_cast<int64_t>(cut - expected_bytes));
    EXPECT_EQ(std::filesystem::file_size(path), expected_bytes);
  }
}

// A flipped bit anywhere in a record's payload or checksum ends the
// reading there, never with a record that was not written.
TEST(RecordFileTest, DamagedRecordEndsTheReading) {
  const std::string whole = Bytes(WriteRecords("damage_source.hsrec", SomeRecords()));
  const std::string path = (ScratchDir("records") / "damaged.hsrec").string();
  int crc_caught = 0;
  for (size_t at = kRecordingMagicBytes + 4; at < whole.size(); ++at) {
    std::string damaged = whole;
    damaged[at] = static_cast<char>(damaged[at] ^ 0x10);
    Overwrite(path, damaged);
    absl::StatusOr<RecordFileContents> read = ReadRecordFile(path);
    ASSERT_TRUE(read.ok());
    ASSERT_TRUE(read->torn()) << at;
    EXPECT_LT(read->whole_bytes, static_cast<int64_t>(at + 1)) << at;
    crc_caught += read->torn_reason.find("CRC32C") != std::string::npos;
  }
  EXPECT_GT(crc_caught, 0);
}

// Not a recording: a clear error naming the file; a missing one: NOT_FOUND.
TEST(RecordFileTest, ForeignAndMissingFilesAreErrors) {
  const std::string path = (ScratchDir("records") / "foreign.hsrec").string();
  Overwrite(path, "SQLite format 3\0 and more");
  absl::StatusOr<RecordFileContents> read = ReadRecordFile(path);
  EXPECT_EQ(read.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(read.status().message().find(path), std::string::npos);
  Overwrite(path, "");
  EXPECT_EQ(ReadRecordFile(path).status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(ReadRecordFile(path + ".missing").status().code(), absl::StatusCode::kNotFound);
  EXPECT_FALSE(CutTornTail(path).ok());
  EXPECT_EQ(std::filesystem::file_size(path), 0u);  // a foreign file is not cut
}

// A length field past the cap is damage, not a request for 4 GiB.
TEST(RecordFileTest, HugeLengthIsTornNotRead) {
  const std::string path = (ScratchDir("records") / "huge.hsrec").string();
  Overwrite(path, std::string(kRecordingMagic, kRecordingMagicBytes) +
                      std::string("\xff\xff\xff\xff\0\0\0\0", 8));
  absl::StatusOr<RecordFileContents> read = ReadRecordFile(path);
  ASSERT_TRUE(read.ok());
  EXPECT_TRUE(read->torn());
  EXPECT_TRUE(read->records.empty());
}

}  // namespace
}  // namespace hs

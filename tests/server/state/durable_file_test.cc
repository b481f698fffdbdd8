#include "server/state/durable_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tests/common/scratch_dir.h"

namespace hs {
namespace {

std::string Contents(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The folder holds only these files: no temporary file is left beside them.
void ExpectOnly(const std::filesystem::path& dir, size_t files) {
  size_t count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    ++count;
    EXPECT_NE(entry.path().filename().string().front(), '.') << entry.path();
  }
  EXPECT_EQ(count, files);
}

// A new file holds the bytes given, binary and empty ones included; writing
// again replaces them whole.
TEST(DurableFileTest, WritesAndReplaces) {
  const std::filesystem::path dir = ScratchDir("durable_file");
  const std::string path = (dir / "catalogue.bin").string();
  const std::string binary("a\0b\xff\n", 5);
  ASSERT_TRUE(WriteFileDurably(path, binary).ok());
  EXPECT_EQ(Contents(path), binary);
  const std::string big(3 << 20, 'z');
  ASSERT_TRUE(WriteFileDurably(path, big).ok());
  EXPECT_EQ(Contents(path), big);
  ASSERT_TRUE(WriteFileDurably(path, "").ok());
  EXPECT_EQ(Contents(path), "");
  ExpectOnly(dir, 1);
}

// A folder that does not exist, or a target that is a folder, is
// UNAVAILABLE naming the path; the old file and the folder are as before.
TEST(DurableFileTest, FailuresNameThePathAndLeaveNothing) {
  const std::filesystem::path dir = ScratchDir("durable_file_fail");
  const std::string missing = (dir / "no_such_folder" / "file").string();
  absl::Status status = WriteFileDurably(missing, "x");
  EXPECT_EQ(status.code(), absl::StatusCode::kUnavailable);
  EXPECT_NE(status.message().find((dir / "no_such_folder").string()), std::string::npos) << status;
  std::filesystem::create_directory(dir / "taken");
  std::ofstream(dir / "taken" / "inside") << "kept";
  status = WriteFileDurably((dir / "taken").string(), "x");
  EXPECT_EQ(status.code(), absl::StatusCode::kUnavailable);
  EXPECT_NE(status.message().find((dir / "taken").string()), std::string::npos) << status;
  EXPECT_EQ(Contents(dir / "taken" / "inside"), "kept");
  ExpectOnly(dir, 1);
}

// A folder flushes; a missing one is UNAVAILABLE naming it.
TEST(DurableFileTest, SyncFolder) {
  const std::filesystem::path dir = ScratchDir("durable_file_sync");
  EXPECT_TRUE(SyncFolder(dir.string()).ok());
  const absl::Status status = SyncFolder((dir / "gone").string());
  EXPECT_EQ(status.code(), absl::StatusCode::kUnavailable);
  EXPECT_NE(status.message().find("gone"), std::string::npos) << status;
}

}  // namespace
}  // namespace hs

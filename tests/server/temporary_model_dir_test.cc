#include "server/temporary_model_dir.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>

#include "tests/common/scratch_dir.h"

namespace hs {
namespace {

namespace fs = std::filesystem;

// A folder as a server leaves it, with a model and (when `lock`) the lock
// file, which nobody holds.
fs::path LeftFolder(const fs::path& parent, const std::string& name, bool lock) {
  const fs::path folder = parent / name;
  fs::create_directories(folder / TemporaryModelDir::kModels);
  std::ofstream(folder / TemporaryModelDir::kModels / "model.stl") << "solid x\nendsolid x\n";
  if (lock) std::ofstream(folder / TemporaryModelDir::kLockFile);
  return folder;
}

// How many folders `parent` holds.
int Folders(const fs::path& parent) {
  int folders = 0;
  for (const auto& entry : fs::directory_iterator(parent)) folders += entry.is_directory();
  return folders;
}

// The folder is made locked under its parent and removed, with what it
// holds, at the end.
TEST(TemporaryModelDirTest, MadeAndRemoved) {
  const fs::path parent = ScratchDir("made");
  std::string path;
  {
    absl::StatusOr<TemporaryModelDir> dir = TemporaryModelDir::Make(parent);
    ASSERT_TRUE(dir.ok()) << dir.status();
    path = dir->path();
    const fs::path root = fs::path(path).parent_path();
    EXPECT_EQ(root.parent_path(), parent);
    EXPECT_EQ(root.filename().string().rfind(TemporaryModelDir::kPrefix, 0), 0u);
    EXPECT_EQ(fs::path(path).filename(), TemporaryModelDir::kModels);
    EXPECT_TRUE(fs::exists(root / TemporaryModelDir::kLockFile));
    std::ofstream(fs::path(path) / "upload.stl") << "x";
    // A running server's folder is not abandoned.
    EXPECT_EQ(RemoveAbandonedModelDirs(parent), 0);
    const TemporaryModelDir moved = *std::move(dir);
    EXPECT_EQ(moved.path(), path);
  }
  EXPECT_FALSE(fs::exists(fs::path(path).parent_path()));
}

// Only folders of the prefix whose lock file is free go: one held by an
// open lock stays, as do one with no lock file (being made), one whose
// lock file is a link, a plain file of the name and others' folders.
TEST(TemporaryModelDirTest, OnlyAbandonedFoldersAreRemoved) {
  const fs::path parent = ScratchDir("abandoned");
  const fs::path dead = LeftFolder(parent, "haptic-models-dead01", true);
  const fs::path held = LeftFolder(parent, "haptic-models-held01", true);
  const fs::path making = LeftFolder(parent, "haptic-models-made01", false);
  const fs::path other = LeftFolder(parent, "other-models-dead01", true);
  std::ofstream(parent / "haptic-models-file");
  // A lock file that is a link to a file nobody locks: not followed.
  const fs::path linked = LeftFolder(parent, "haptic-models-link01", false);
  std::ofstream(parent / "free.lock");
  fs::create_symlink(parent / "free.lock", linked / TemporaryModelDir::kLockFile);
  const int fd = open((held / TemporaryModelDir::kLockFile).c_str(), O_RDWR);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(flock(fd, LOCK_EX | LOCK_NB), 0);
  EXPECT_EQ(RemoveAbandonedModelDirs(parent), 1);
  close(fd);
  EXPECT_FALSE(fs::exists(dead));
  for (const fs::path& kept : {held, making, other, linked}) {
    EXPECT_TRUE(fs::exists(kept / TemporaryModelDir::kModels / "model.stl")) << kept;
  }
  EXPECT_TRUE(fs::exists(parent / "haptic-models-file"));
}

// A server killed with SIGKILL leaves its folder; the next one to start
// removes it.
TEST(TemporaryModelDirTest, AKilledServersFolderGoesAtTheNextStart) {
  const fs::path parent = ScratchDir("killed");
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    absl::StatusOr<TemporaryModelDir> dir = TemporaryModelDir::Make(parent);
    if (!dir.ok()) _exit(1);
    raise(SIGKILL);
    _exit(2);
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL) << status;
  ASSERT_EQ(Folders(parent), 1);
  absl::StatusOr<TemporaryModelDir> next = TemporaryModelDir::Make(parent);
  ASSERT_TRUE(next.ok()) << next.status();
  EXPECT_EQ(Folders(parent), 1);  // the new server's own
}

// A parent that is not a folder: UNAVAILABLE, nothing made.
TEST(TemporaryModelDirTest, UnwritableParentIsUnavailable) {
  const fs::path parent = ScratchDir("file") / "not-a-folder";
  std::ofstream(parent) << "x";
  absl::StatusOr<TemporaryModelDir> dir = TemporaryModelDir::Make(parent);
  EXPECT_EQ(dir.status().code(), absl::StatusCode::kUnavailable);
}

}  // namespace
}  // namespace hs

#include "server/temporary_model_dir.h"

#include <fcntl.h>
#include <stdlib.h>
#include <sys/file.h>
#include <unistd.h>

#include <system_error>
#include <utility>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"

namespace hs {
namespace {

// Whether `folder`'s lock file exists and no process holds its lock. The
// temporary folder is everyone's: a "lock file" that is a link (to a
// device, a pipe) is not followed, nor waited on.
bool Abandoned(const std::filesystem::path& folder) {
  const std::string lock = (folder / TemporaryModelDir::kLockFile).string();
  const int fd = open(lock.c_str(), O_RDWR | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK);
  if (fd < 0) return false;
  const bool free = flock(fd, LOCK_EX | LOCK_NB) == 0;
  close(fd);
  return free;
}

}  // namespace

int RemoveAbandonedModelDirs(const std::filesystem::path& parent) {
  int removed = 0;
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(parent, error)) {
    if (!absl::StartsWith(entry.path().filename().string(), TemporaryModelDir::kPrefix)) continue;
    if (!entry.is_directory(error) || entry.is_symlink(error)) continue;
    if (!Abandoned(entry.path())) continue;
    // Another server starting at once may remove it first: either is fine.
    if (std::filesystem::remove_all(entry.path(), error) > 0) ++removed;
  }
  return removed;
}

absl::StatusOr<TemporaryModelDir> TemporaryModelDir::Make(const std::filesystem::path& parent) {
  RemoveAbandonedModelDirs(parent);
  std::string pattern = (parent / absl::StrCat(kPrefix, "XXXXXX")).string();
  if (mkdtemp(pattern.data()) == nullptr) {
    return absl::UnavailableError(
        absl::StrCat("cannot make a folder for uploaded models under ", parent.string()));
  }
  const std::filesystem::path root(pattern);
  const std::string lock = (root / kLockFile).string();
  const int fd = open(lock.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0600);
  std::error_code error;
  if (fd < 0 || flock(fd, LOCK_EX | LOCK_NB) != 0 ||
      !std::filesystem::create_directory(root / kModels, error)) {
    if (fd >= 0) close(fd);
    std::filesystem::remove_all(root, error);
    return absl::UnavailableError(
        absl::StrCat("cannot prepare the folder of uploaded models ", pattern));
  }
  return TemporaryModelDir(std::move(pattern), fd);
}

TemporaryModelDir::TemporaryModelDir(TemporaryModelDir&& other) noexcept
    : root_(std::exchange(other.root_, "")), lock_fd_(std::exchange(other.lock_fd_, -1)) {}

TemporaryModelDir& TemporaryModelDir::operator=(TemporaryModelDir&& other) noexcept {
  if (this != &other) {
    Release();
    root_ = std::exchange(other.root_, "");
    lock_fd_ = std::exchange(other.lock_fd_, -1);
  }
  return *this;
}

TemporaryModelDir::~TemporaryModelDir() { Release(); }

void TemporaryModelDir::Release() {
  if (!root_.empty()) {
    std::error_code error;
    std::filesystem::remove_all(root_, error);
    root_.clear();
  }
  if (lock_fd_ >= 0) {
    close(lock_fd_);  // after the removal: no other server takes it meanwhile
    lock_fd_ = -1;
  }
}

}  // namespace hs

#pragma once
// The folder of uploaded models of a server with no --model-dir or
// --state-dir: made under the system's temporary folder, removed when the
// server ends. A server killed with SIGKILL cannot remove its own, so each
// server's folder holds a lock file it keeps locked (flock) while it runs,
// beside the models' folder (whose dot files the model store removes), and
// the next server to start removes every such folder whose lock is free:
// its owner is gone, whatever became of its process id.

#include <filesystem>
#include <string>
#include <utility>

#include "absl/status/statusor.h"

namespace hs {

class TemporaryModelDir {
 public:
  /// Removes the abandoned folders under `parent`, then makes and locks a
  /// new one there. UNAVAILABLE when it cannot.
  static absl::StatusOr<TemporaryModelDir> Make(
      const std::filesystem::path& parent = std::filesystem::temp_directory_path());
  TemporaryModelDir(TemporaryModelDir&& other) noexcept;
  TemporaryModelDir& operator=(TemporaryModelDir&& other) noexcept;
  TemporaryModelDir(const TemporaryModelDir&) = delete;
  TemporaryModelDir& operator=(const TemporaryModelDir&) = delete;
  /// Removes the folder and what it holds.
  ~TemporaryModelDir();

  /// The models' folder: kModels in the server's own.
  std::string path() const { return (std::filesystem::path(root_) / kModels).string(); }

  /// The name every server's folder starts with, and what it holds.
  static constexpr const char* kPrefix = "haptic-models-";
  static constexpr const char* kLockFile = "owner.lock";
  static constexpr const char* kModels = "models";

 private:
  TemporaryModelDir(std::string root, int lock_fd) : root_(std::move(root)), lock_fd_(lock_fd) {}
  void Release();

  std::string root_;  // the server's own folder
  int lock_fd_ = -1;
};

/// Removes every folder under `parent` named TemporaryModelDir::kPrefix...
/// whose lock file no process holds; folders without one (being made, or
/// not ours) stay. Returns how many it removed.
int RemoveAbandonedModelDirs(const std::filesystem::path& parent);

}  // namespace hs

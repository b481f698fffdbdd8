#include "server/recording/recording_folder.h"

#include <filesystem>
#include <iostream>

#include "absl/strings/str_cat.h"
#include "common/recording/record_file.h"

namespace hs {

absl::Status PrepareRecordingFolder(const std::string& dir) {
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (error) {
    return absl::UnavailableError(
        absl::StrCat("cannot make the recording folder ", dir, ": ", error.message()));
  }
  for (const auto& entry : std::filesystem::directory_iterator(dir, error)) {
    if (!entry.is_regular_file() || entry.path().extension() != ".hsrec") continue;
    const absl::StatusOr<int64_t> cut = CutTornTail(entry.path().string());
    if (!cut.ok()) {
      std::cerr << "haptic-server: recording " << entry.path().string()
                << " left as it is: " << cut.status().message() << "\n";
    } else if (*cut > 0) {
      std::cerr << "haptic-server: recording " << entry.path().string()
                << " was cut short by a crash: its torn last " << *cut << " bytes removed\n";
    }
  }
  return absl::OkStatus();
}

}  // namespace hs

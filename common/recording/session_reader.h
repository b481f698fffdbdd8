#pragma once
// Reads a recorded session: the file given and the parts after it, up to
// the first torn one (a crash cut it: no part can follow).

#include <cstdint>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "haptics/v1/recording.pb.h"

namespace hs {

/// One file of a session as read.
struct SessionFile {
  std::string path;
  int part = 0;
  int64_t bytes = 0;
  /// Bytes up to the end of its last whole record.
  int64_t whole_bytes = 0;
  /// Why reading stopped before its end; "" for a whole file.
  std::string torn_reason;
};

struct RecordedSession {
  std::vector<SessionFile> files;
  /// Every whole record of the files, in order; each file's first is its
  /// RecordingStart.
  std::vector<haptics::v1::Record> records;
};

/// NOT_FOUND for a missing file; INVALID_ARGUMENT naming the file for one
/// that is not a recording or does not begin with its session's start, or
/// parts out of order.
absl::StatusOr<RecordedSession> ReadSession(const std::string& file);

}  // namespace hs

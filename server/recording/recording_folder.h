#pragma once
// The folder of session recordings, made ready at start.

#include <string>

#include "absl/status/status.h"

namespace hs {

/// Creates `dir` when missing and cuts the torn tail off each recording a
/// crash left in it (saying so on stderr), so that every file there ends
/// in a whole record. UNAVAILABLE naming the folder when it cannot be
/// made; a file that cannot be cut is named on stderr and left as it is.
absl::Status PrepareRecordingFolder(const std::string& dir);

}  // namespace hs

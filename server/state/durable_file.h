#pragma once
// Files that are whole on disk or not there at all: written to a temporary
// file beside the target, flushed to the disk, renamed over the target,
// and the folder flushed, so that a crash at any point leaves the old file
// or the new one, never a part.

#include <string>
#include <string_view>

#include "absl/status/status.h"

namespace hs {

/// Writes `bytes` to `path` durably (see above). UNAVAILABLE naming the
/// path and the system's reason on failure; no temporary file is left.
absl::Status WriteFileDurably(const std::string& path, std::string_view bytes);

/// Flushes the folder `dir` itself (its entries: a rename or removal in
/// it) to the disk. UNAVAILABLE naming it on failure.
absl::Status SyncFolder(const std::string& dir);

}  // namespace hs

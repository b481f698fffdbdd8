#pragma once
// Device paths: one pose per line, "x,y,z,rx,ry,rz" (metres, then a
// rotation vector in radians), '#' starts a comment, blank lines skipped.
// Read by `simulate` (offline) and `drive` (against a server).

#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "common/core/types.h"

namespace hs::cli {

/// The poses of `path`, in order; none for an empty path. NOT_FOUND when
/// the file cannot be opened, INVALID_ARGUMENT naming the line otherwise.
absl::StatusOr<std::vector<Isometry3d>> ReadToolPath(const std::string& path);

}  // namespace hs::cli

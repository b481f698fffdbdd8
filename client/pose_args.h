#pragma once
// Parsing the numbers users type on the command line: vectors "x,y,z" and
// poses "x,y,z,rx,ry,rz" (translation in metres, then a rotation vector:
// axis times angle in radians).

#include <string_view>
#include <vector>

#include "absl/status/statusor.h"
#include "common/core/types.h"

namespace hs::cli {

/// Exactly `count` comma-separated finite numbers. INVALID_ARGUMENT
/// otherwise.
absl::StatusOr<std::vector<double>> ParseNumbers(std::string_view text, size_t count);

/// Three comma-separated finite numbers. INVALID_ARGUMENT otherwise.
absl::StatusOr<Vector3d> ParseVector3(std::string_view text);

/// Six comma-separated finite numbers: translation, then rotation vector.
/// INVALID_ARGUMENT otherwise.
absl::StatusOr<Isometry3d> ParsePose(std::string_view text);

/// The pose with translation `p_m` (metres) and rotation `rotation_vector`
/// (axis times angle, radians).
Isometry3d PoseFromNumbers(const Vector3d& p_m, const Vector3d& rotation_vector);

}  // namespace hs::cli

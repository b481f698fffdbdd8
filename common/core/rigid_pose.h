#pragma once
// The check every pose gets at the edge of a layer: finite, and a rotation
// (orthonormal, right-handed) rather than any linear map.

#include <string>
#include <string_view>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "common/core/types.h"

namespace hs {

/// OK, or INVALID_ARGUMENT naming `what` when `X` has a non-finite entry or
/// its linear part is not a rotation (within 1e-9).
inline absl::Status ValidateRigidPose(const Isometry3d& X, std::string_view what) {
  if (!X.matrix().allFinite()) {
    return absl::InvalidArgumentError(absl::StrCat(std::string(what), " pose is not finite"));
  }
  const Matrix3d R = X.linear();
  if (!(R.transpose() * R).isIdentity(1e-9) || R.determinant() < 0) {
    return absl::InvalidArgumentError(
        absl::StrCat(std::string(what), " pose rotation is not a rotation"));
  }
  return absl::OkStatus();
}

}  // namespace hs

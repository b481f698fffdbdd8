#pragma once
// Test helper: a pose that only translates.

#include "common/core/types.h"

namespace hs {

/// X_WO translating by (x, y, z) metres, no rotation.
inline Isometry3d At(double x, double y, double z) {
  Isometry3d X = Isometry3d::Identity();
  X.translation() = Vector3d(x, y, z);
  return X;
}

}  // namespace hs

#pragma once
// A rigid pose in plain numbers: what a device reports and frames carry.

namespace haptics {

/// World frame: position in metres, orientation a unit quaternion
/// (w, x, y, z).
struct Pose {
  double position_m[3] = {0, 0, 0};
  double orientation_wxyz[4] = {1, 0, 0, 0};
};

}  // namespace haptics

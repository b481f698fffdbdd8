#pragma once
// The god object's slide rule, shared by the server's proxy
// (common/sim/proxy.cc) and a device's loop on the local model
// (client/haptic_loop, which links no simulation: header only, Eigen only).

#include <optional>

#include "common/core/types.h"

namespace hs {

/// Coulomb coefficients of a touched surface, or none (no friction).
struct SlideFriction {
  double static_friction = 0;
  double dynamic_friction = 0;
};

/// Where a proxy at `p`, touching a surface of unit normal `n` (out of it),
/// goes next toward the device at `device`: the device itself when the
/// device is not behind the surface; else along the surface, dropping the
/// part of the way into it, and with `friction` lagging the device by the
/// dynamic friction; nothing when it sticks (inside the static cone).
inline std::optional<Vector3d> SlideGoal(const Vector3d& p, const Vector3d& device,
                                         const Vector3d& n,
                                         const std::optional<SlideFriction>& friction) {
  const Vector3d rest = device - p;
  const double into = -rest.dot(n);
  if (into <= 0) return device;
  Vector3d along = rest + into * n;
  if (friction) {
    const double length = along.norm();
    if (length <= friction->static_friction * into) return std::nullopt;
    along *= (length - friction->dynamic_friction * into) / length;
  }
  return p + along;
}

}  // namespace hs

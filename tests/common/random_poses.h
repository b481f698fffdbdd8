#pragma once
// Test helper: random rigid poses and directions from a caller's seeded
// generator, so that property tests over poses stay reproducible.

#include <random>

#include "common/core/types.h"

namespace hs::testing_poses {

/// Translation uniform in [-reach, reach]^3, rotation by up to 3 rad about
/// a uniformly drawn axis.
inline Isometry3d RandomPose(std::mt19937& rng, double reach) {
  std::uniform_real_distribution<double> u(-1, 1);
  Isometry3d X = Isometry3d::Identity();
  X.translate(reach * Vector3d(u(rng), u(rng), u(rng)));
  X.rotate(Eigen::AngleAxisd(3.0 * u(rng), Vector3d(u(rng), u(rng), u(rng)).normalized()));
  return X;
}

/// A unit vector uniform on the sphere.
inline Vector3d RandomDirection(std::mt19937& rng) {
  std::normal_distribution<double> n(0, 1);
  return Vector3d(n(rng), n(rng), n(rng)).normalized();
}

}  // namespace hs::testing_poses

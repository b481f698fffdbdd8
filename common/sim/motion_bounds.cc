#include "common/sim/motion_bounds.h"

#include <algorithm>
#include <cmath>

namespace hs {
namespace {

// The farthest corner of `object`'s box from its frame origin, metres.
double Radius(const HapticObject& object) {
  const AlignedBox3d& box = object.bounding_box();
  return box.min().cwiseAbs().cwiseMax(box.max().cwiseAbs()).norm();
}

double TurnAngle(const Isometry3d& X_from, const Isometry3d& X_to) {
  return Eigen::AngleAxisd(X_from.linear().transpose() * X_to.linear()).angle();
}

}  // namespace

AlignedBox3d WorldBox(const HapticObject& object, const Isometry3d& X_WO) {
  const AlignedBox3d& box = object.bounding_box();
  // The world box of a rotated box: centre moved, half sizes through |R|.
  const Vector3d centre = X_WO * box.center();
  const Vector3d half = X_WO.linear().cwiseAbs() * (box.sizes() / 2);
  return AlignedBox3d(centre - half, centre + half);
}

double Travel(const HapticObject& object, const Isometry3d& X_WO_from, const Isometry3d& X_WO_to) {
  return (X_WO_to.translation() - X_WO_from.translation()).norm() +
         TurnAngle(X_WO_from, X_WO_to) * Radius(object);
}

AlignedBox3d SweptBox(const HapticObject& object, const Isometry3d& X_WO_from,
                      const Isometry3d& X_WO_to) {
  AlignedBox3d box = WorldBox(object, X_WO_from).extend(WorldBox(object, X_WO_to));
  // A point's interpolated position is within s x turn of its path without
  // turning, which is within s x turn of the two boxes' hull.
  const double turn = 2 * TurnAngle(X_WO_from, X_WO_to) * Radius(object);
  if (turn > 0) {
    box.min().array() -= turn;
    box.max().array() += turn;
  }
  return box;
}

Isometry3d InterpolatePose(const Isometry3d& X_from, const Isometry3d& X_to, double s) {
  Isometry3d X = Isometry3d::Identity();
  const Eigen::Quaterniond q_from(X_from.linear()), q_to(X_to.linear());
  X.linear() = q_from.slerp(s, q_to).normalized().toRotationMatrix();
  X.translation() = (1 - s) * X_from.translation() + s * X_to.translation();
  return X;
}

int SubstepCount(double travel_m, double max_travel_m, int max_substeps) {
  if (!(max_travel_m > 0) || !(travel_m >= 0)) return 1;
  const double count = 1 + std::floor(travel_m / max_travel_m);
  return static_cast<int>(std::clamp(count, 1.0, static_cast<double>(max_substeps)));
}

}  // namespace hs

#pragma once
// Internal to common/contact: a contact as the reconstruction methods find
// it, every vector and point in the fixed object's frame F
// (docs/algorithm.md). ComputeContact turns it into a ContactSet, world
// frame, once.

#include <array>
#include <limits>
#include <span>
#include <vector>

#include "common/contact/contact_set.h"

namespace hs {

/// A ContactPoint in F's frame.
struct ContactPointF {
  /// The point, F's frame, metres, with M moved by the reversing vector.
  Vector3d p_FC = Vector3d::Zero();
  Feature moving;
  Feature fixed;
};

/// What ContactSet reports (see there for each field), in F's frame. The
/// method, tolerance and time of impact are the caller's.
struct ContactSetF {
  bool colliding = false;
  bool penetrating = false;
  double depth_m = 0;
  Vector3d direction_F = Vector3d::Zero();
  Vector3d reversing_vector_F = Vector3d::Zero();
  Vector3d normal_F = Vector3d::Zero();
  SideContact moving;
  SideContact fixed;
  std::vector<ContactPointF> points;
  bool singular_case = false;
  bool fallback = false;
  std::array<double, 3> plane_depths_m = {std::numeric_limits<double>::infinity(),
                                          std::numeric_limits<double>::infinity(),
                                          std::numeric_limits<double>::infinity()};
};

/// `found` in the world, F posed at X_WF, written over `set`: the one place
/// a contact leaves F's frame (ComputeContact's last step). Method,
/// tolerance and time of impact are left as they are.
void ToWorld(const ContactSetF& found, const Isometry3d& X_WF, ContactSet& set);

/// `points` in the world, F posed at X_WF, into `out` (cleared first).
void PointsToWorld(std::span<const ContactPointF> points, const Isometry3d& X_WF,
                   std::vector<ContactPoint>& out);

}  // namespace hs

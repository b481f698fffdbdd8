#pragma once
// Closest points between a point and a triangle, and between two segments:
// what locating contact features needs. Hand-written (after Ericson,
// Real-Time Collision Detection, 5.1.5 and 5.1.9) because FCL keeps its
// versions in internal detail namespaces with unstable signatures.

#include "common/core/types.h"

namespace hs {

/// The point of triangle (a, b, c) closest to `p`. Degenerate triangles are
/// handled (the closest point of their segments), and so are slivers (twice
/// the area at most 1e-4 times the longest edge squared), on which the
/// usual region tests would be decided by rounding.
Vector3d ClosestPointOnTriangle(const Vector3d& p, const Vector3d& a, const Vector3d& b,
                                const Vector3d& c);

/// The point of segment [a, b] closest to `p`.
Vector3d ClosestPointOnSegment(const Vector3d& p, const Vector3d& a, const Vector3d& b);

struct SegmentClosest {
  /// Parameters in [0, 1] along each segment and the points they give.
  double s = 0, t = 0;
  Vector3d on_first = Vector3d::Zero(), on_second = Vector3d::Zero();
};

/// Closest points of segments [p1, q1] and [p2, q2]. For parallel segments
/// one of the closest pairs is returned.
SegmentClosest ClosestPointsOfSegments(const Vector3d& p1, const Vector3d& q1, const Vector3d& p2,
                                       const Vector3d& q2);

}  // namespace hs

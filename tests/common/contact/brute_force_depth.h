#pragma once
// Test and benchmark oracle: the exact 3D method's depth t* (see
// docs/algorithm.md and common/contact/sweep_method.cc) by brute force in
// long double. Every triangle pair of the two objects is swept (no
// hierarchy, no candidate search), so a pair the method's queries never
// visited still counts. Slow by design: O(faces x faces).

#include <cstdint>

#include "common/contact/contact_query.h"

namespace hs::reference {

/// What the brute force found for one pose and direction.
struct BruteForceDepth {
  /// Some pair of triangles meets at t = 0 (within the tolerance).
  bool colliding = false;
  /// t*, metres: the end of the run of pairs' sweep intervals that covers
  /// t = 0, runs chaining across gaps up to the tolerance (as the method's).
  /// 0 when not colliding.
  long double depth_m = 0;
  /// The touching tolerance used, metres (ContactSet::tolerance_m's rule).
  long double tolerance_m = 0;
  /// Pairs swept (faces of moving x faces of fixed) and pairs whose sweep
  /// interval reaches t >= 0.
  int64_t pairs = 0;
  int64_t meeting_pairs = 0;
};

/// t* of `moving` backed out of `fixed` along -direction_W (any nonzero
/// length; it is normalized), both posed in the world. Only the objects and
/// poses are read (the collision models are not). Like the method, it sees
/// surfaces only: an object wholly inside the other without a crossing is
/// not colliding. `relative_tolerance` as ContactQuery's.
BruteForceDepth ComputeBruteForceDepth(const PosedObject& moving, const PosedObject& fixed,
                                       const Vector3d& direction_W, double relative_tolerance);

}  // namespace hs::reference

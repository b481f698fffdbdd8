#pragma once
// Internal to common/contact: what every reconstruction method starts from.
// Everything is in the fixed object's frame F (docs/algorithm.md).

#include <vector>

#include "common/collision/collision_model.h"
#include "common/collision/triangle_pairs.h"
#include "common/collision/triangle_sat.h"
#include "common/hds/haptic_object.h"

namespace hs {

struct ContactContext {
  const HapticObject& moving;
  const CollisionModel& moving_model;
  const HapticObject& fixed;
  const CollisionModel& fixed_model;
  /// Pose of the moving object M in F's frame.
  Isometry3d X_FM;
  /// Unit direction of M's motion relative to F, in F's frame.
  Vector3d direction_F;
  /// Touching distance, metres.
  double tolerance_m = 0;
  /// Face pairs (a: face of M, b: face of F) intersecting within the
  /// tolerance at the current pose; not empty.
  std::vector<TrianglePair> pairs;
  /// ContactQuery::depth_hint_m, metres along direction_F from X_FM; 0: none.
  double depth_hint_m = 0;
  /// The pair's cache for its static pair queries (M first, F second), or
  /// none: the answers are the same.
  PairCache* pair_cache = nullptr;

  /// Face `f` of M, in F's frame, at the current pose.
  Triangle3d MovingTriangle(FaceId f) const;
  /// Face `f` of F, in F's frame (inline: taken per pair on the hot path).
  Triangle3d FixedTriangle(FaceId f) const {
    const TriangleCorners c = FixedCorners(f);
    return {*c[0], *c[1], *c[2]};
  }
  /// Where face `f` of F's corners are kept (F's own vertices).
  TriangleCorners FixedCorners(FaceId f) const {
    const auto& v = fixed.face(f).vertices;
    return {&fixed.position(v[0]), &fixed.position(v[1]), &fixed.position(v[2])};
  }
  /// The sum of the unit normals of the fixed faces in `pairs` (outward for
  /// a consistently oriented mesh), F's frame.
  Vector3d TouchedFixedNormals() const;
};

}  // namespace hs

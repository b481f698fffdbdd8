#pragma once
// Narrow phase: every pair of faces of two objects that intersect.

#include <optional>
#include <span>
#include <vector>

#include "common/collision/collision_model.h"
#include "common/collision/pair_cache.h"
#include "common/core/types.h"

namespace hs {

/// A face of object A and a face of object B that intersect or touch.
struct TrianglePair {
  FaceId a = 0;
  FaceId b = 0;
  bool operator==(const TrianglePair&) const = default;
  auto operator<=>(const TrianglePair&) const = default;
};

/// Appends to `pairs` every face pair of `a` posed at X_WA and `b` posed at
/// X_WB (world frame, metres) that intersect or are closer than `margin_m`
/// along every separating axis, in no particular order. Both models must
/// share a bounding volume type, and `margin_m` must not exceed the sum of
/// their margins (else pairs within it could be culled). The pairs in
/// `skip` (sorted; faces of `a` and `b`), which the caller has decided
/// already, are left out untested. Returns the number of bounding-volume tests made.
///
/// With a `cache` kept for these two models, a query near the pose of an
/// earlier one tests only the pairs that could meet there (pair_cache.h)
/// and appends the same pairs in the same order as without it, save where
/// the hierarchy culls a pair the face test accepts (faces farther apart
/// than the models' margins that no tested axis separates by the margin,
/// which needs a sliver or near-parallel edges 1,000 times longer than the
/// gap; then the cache's answer holds the pair, as the contract above says).
int64_t FindIntersectingTriangles(const CollisionModel& a, const Isometry3d& X_WA,
                                  const CollisionModel& b, const Isometry3d& X_WB, double margin_m,
                                  std::vector<TrianglePair>& pairs,
                                  std::span<const TrianglePair> skip = {},
                                  PairCache* cache = nullptr);

/// What a swept query's face test asks of a pair whose boxes meet.
enum class SweptFaceTest {
  kEveryAxis,   // that the faces meet: exactly the pairs that do
  kPlanesOnly,  // that neither face stays beyond the other's plane all along:
                // a superset, for callers that find each pair's exact
                // interval themselves and would only repeat the axes
};

/// Like FindIntersectingTriangles for a translating A: appends every face
/// pair that intersects (within `margin_m`) at some instant while A moves in
/// a straight line from X_WA translated by -sweep_W to X_WA (sweep_W: world
/// frame, metres). Exact for the motion, so a thin object passed through in
/// one step is found; with SweptFaceTest::kPlanesOnly, those and others
/// whose planes do not rule them out. Leaves out the pairs in `skip`
/// (sorted; faces of `a` and `b`), untested.
/// Returns the number of bounding-volume tests made.
int64_t FindSweptTrianglePairs(const CollisionModel& a, const Isometry3d& X_WA,
                               const Vector3d& sweep_W, const CollisionModel& b,
                               const Isometry3d& X_WB, double margin_m,
                               std::vector<TrianglePair>& pairs,
                               std::span<const TrianglePair> skip = {},
                               SweptFaceTest face_test = SweptFaceTest::kEveryAxis);

/// Whether FindIntersectingTriangles (no `sweep_W`) or FindSweptTrianglePairs
/// would find any pair: the same test, stopped at the first pair found.
bool AnyTrianglesMeet(const CollisionModel& a, const Isometry3d& X_WA,
                      const std::optional<Vector3d>& sweep_W, const CollisionModel& b,
                      const Isometry3d& X_WB, double margin_m);

}  // namespace hs

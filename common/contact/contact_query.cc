#include "common/contact/contact_query.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <utility>
#include <vector>

#include "absl/cleanup/cleanup.h"
#include "absl/strings/str_cat.h"
#include "common/collision/pair_cache.h"
#include "common/collision/triangle_pairs.h"
#include "common/collision/triangle_sat.h"
#include "common/contact/contact_context.h"
#include "common/contact/contact_features.h"
#include "common/contact/contact_set_f.h"
#include "common/contact/paper_method.h"
#include "common/contact/sweep_method.h"
#include "common/core/check.h"
#include "common/core/rigid_pose.h"
#include "common/core/scratch.h"
#include "common/core/status_macros.h"

namespace hs {
namespace {

// `v`'s length, and `v` over it. From about 1e154 m on, v's squared norm
// overflows, and norm() would be infinite and normalized() zero, so such a
// v is scaled down first (Eigen's stable forms); below that, the plain
// forms' own roundings.
double LengthOf(const Vector3d& v) {
  return std::isfinite(v.squaredNorm()) ? v.norm() : v.stableNorm();
}
Vector3d UnitAlong(const Vector3d& v) {
  return std::isfinite(v.squaredNorm()) ? v.normalized() : v.stableNormalized();
}

// With no motion to reverse, push back against the fixed faces the moving
// object is in: D points into F, opposite their mean outward normal; failing
// that, from M's centre toward F's.
Vector3d FallbackDirection(const ContactContext& c) {
  const Vector3d sum = -c.TouchedFixedNormals();
  if (sum.squaredNorm() > 1e-24) return sum.normalized();
  const Vector3d towards =
      c.fixed.bounding_box().center() - c.X_FM * c.moving.bounding_box().center();
  return towards.squaredNorm() > 0 ? towards.normalized() : Vector3d::UnitZ();
}

// For M moving by `step_F` into its current pose: the largest t in [0, 1]
// at which a pair intersects, found by the swept query, so M touched F first
// at the fraction 1 - t of the step. Exact intervals (zero margin), so that
// M moved back by t touches F within any tolerance; none when the query
// found only near misses, or nothing. `swept` gets the pairs that meet
// within the tolerance somewhere along the step.
std::optional<double> LatestTouchBack(const ContactContext& c, const Vector3d& step_F,
                                      std::vector<TrianglePair>& swept) {
  FindSweptTrianglePairs(c.moving_model, c.X_FM, step_F, c.fixed_model, Isometry3d::Identity(),
                         c.tolerance_m, swept);
  std::optional<double> latest;
  for (const TrianglePair& pair : swept) {
    const Interval i =
        SweptIntersection(c.MovingTriangle(pair.a), c.FixedTriangle(pair.b), step_F, 0.0, {0, 1});
    if (!i.empty()) latest = std::max(latest.value_or(0.0), i.hi);
  }
  return latest;
}

// The pairs within the tolerance at c.X_FM, taken from `swept`, the pairs
// met along a step through c.X_FM: every pair the pair query would find
// there is among them, so their leaf test alone gives its answer.
void MeetingAt(ContactContext& c, std::span<const TrianglePair> swept) {
  c.pairs.clear();
  for (const TrianglePair& pair : swept) {
    if (TrianglesIntersect(c.MovingTriangle(pair.a), c.FixedTriangle(pair.b), c.tolerance_m)) {
      c.pairs.push_back(pair);
    }
  }
}

}  // namespace

Triangle3d ContactContext::MovingTriangle(FaceId f) const {
  const auto& v = moving.face(f).vertices;
  return {X_FM * moving.position(v[0]), X_FM * moving.position(v[1]), X_FM * moving.position(v[2])};
}

Vector3d ContactContext::TouchedFixedNormals() const {
  Vector3d sum = Vector3d::Zero();
  for (const TrianglePair& pair : pairs) {
    const Vector3d n = TriangleNormal(FixedTriangle(pair.b));
    if (n.squaredNorm() > 0) sum += n.normalized();
  }
  return sum;
}

absl::Status CheckObjectSize(const HapticObject& object) {
  const double across = object.bounding_box().diagonal().norm();
  if (!(across >= kMinObjectSizeM)) {
    return absl::InvalidArgumentError(absl::StrCat("is ", across, " m across, under the ",
                                                   kMinObjectSizeM, " m a contact query takes"));
  }
  return absl::OkStatus();
}

namespace {

// Buffers kept from query to query (common/core/scratch.h): FindFirstTouch's,
// and ComputeContact's.
struct FirstTouchBuffers {
  std::vector<TrianglePair> swept;
  LocatedContacts located;
};
struct ContactBuffers {
  std::vector<TrianglePair> pairs, swept;
  ContactSetF found;
  PairCache own_cache;  // a query's without a cache of its own (OwnCache)
};

// How far M (at X_FM) can back out along the unit `direction_F`, moved by
// -t direction_F, and still meet F within `tolerance_m`: past it, M's box
// lies beyond F's along the direction. Every sweep interval of the exact
// method ends by then.
double DepthBound(const HapticObject& moving, const Isometry3d& X_FM, const HapticObject& fixed,
                  const Vector3d& direction_F, double tolerance_m) {
  double moving_hi = -std::numeric_limits<double>::infinity();
  double fixed_lo = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 8; ++k) {
    const auto corner = static_cast<AlignedBox3d::CornerType>(k);
    moving_hi = std::max(moving_hi, direction_F.dot(X_FM * moving.bounding_box().corner(corner)));
    fixed_lo = std::min(fixed_lo, direction_F.dot(fixed.bounding_box().corner(corner)));
  }
  return moving_hi - fixed_lo + tolerance_m;
}

// The cache the exact method's pair queries go through when the caller
// keeps none: when M can back out no further than a region's skin
// (DepthBound), one kept for this query alone, so that the query where M
// backs out to is answered from the candidates of the one at the pose
// rather than by a second traversal. The answers are the same.
PairCache* OwnCache(const ContactContext& c, const Vector3d& direction_F, PairCache& own) {
  const double depth = DepthBound(c.moving, c.X_FM, c.fixed, direction_F, c.tolerance_m);
  if (!(depth > 0 && depth < PairCache::DefaultSkin(c.moving_model, c.fixed_model))) {
    return nullptr;
  }
  // Backed out by t <= depth, M's centre moves t along a unit direction,
  // up to rounding.
  own.Restart(depth * (1 + 1e-6));
  return &own;
}

// Validates a pair query and returns its touching tolerance in metres.
absl::StatusOr<double> PairTolerance(const PosedObject& moving, const PosedObject& fixed,
                                     const Vector3d& direction_W, double relative_tolerance) {
  HS_CHECK(moving.object && moving.model && fixed.object && fixed.model);
  HS_RETURN_IF_ERROR(ValidateRigidPose(moving.X_WO, "moving object"));
  HS_RETURN_IF_ERROR(ValidateRigidPose(fixed.X_WO, "fixed object"));
  if (!direction_W.allFinite()) {
    return absl::InvalidArgumentError("direction is not finite");
  }
  if (!(std::isfinite(relative_tolerance) && relative_tolerance >= 0)) {
    return absl::InvalidArgumentError("relative tolerance must be finite and >= 0");
  }
  if (moving.model->bv_type() != fixed.model->bv_type()) {
    return absl::InvalidArgumentError("the two collision models use different bounding volumes");
  }
  for (const auto& [object, which] :
       {std::pair{moving.object, "moving"}, std::pair{fixed.object, "fixed"}}) {
    if (absl::Status size = CheckObjectSize(*object); !size.ok()) {
      return absl::InvalidArgumentError(absl::StrCat("the ", which, " object ", size.message()));
    }
  }
  const double moving_across = moving.object->bounding_box().diagonal().norm();
  const double fixed_across = fixed.object->bounding_box().diagonal().norm();
  // The pair's size: the sum of the two objects' box diagonals. Unlike the
  // box around both, it is the same wherever the objects are, so the
  // tolerance is invariant under rigid motion and never outgrows the
  // models' margins when the objects are far apart.
  const double size = moving_across + fixed_across;
  const double tolerance = relative_tolerance * size;
  if (tolerance > moving.model->margin_m() + fixed.model->margin_m()) {
    return absl::InvalidArgumentError(absl::StrCat(
        "tolerance ", tolerance, " m exceeds the collision models' margins (",
        moving.model->margin_m() + fixed.model->margin_m(), " m); build them with larger ones"));
  }
  return tolerance;
}

}  // namespace

absl::StatusOr<bool> AreColliding(const PosedObject& moving, const PosedObject& fixed,
                                  double relative_tolerance,
                                  const std::optional<Vector3d>& step_W) {
  HS_ASSIGN_OR_RETURN(
      const double tolerance,
      PairTolerance(moving, fixed, step_W.value_or(Vector3d::Zero()), relative_tolerance));
  const bool swept = step_W && step_W->squaredNorm() > 0;
  return AnyTrianglesMeet(*moving.model, moving.X_WO, swept ? step_W : std::nullopt, *fixed.model,
                          fixed.X_WO, tolerance);
}

absl::StatusOr<bool> FindFirstTouch(const PosedObject& moving, const PosedObject& fixed,
                                    const Vector3d& step_W, double relative_tolerance,
                                    FirstTouch& touch) {
  HS_ASSIGN_OR_RETURN(const double tolerance,
                      PairTolerance(moving, fixed, step_W, relative_tolerance));
  const Isometry3d X_FW = fixed.X_WO.inverse();
  const Vector3d step_F = X_FW.linear() * step_W;
  if (!(step_F.squaredNorm() > 1e-300)) return false;
  ContactContext context{*moving.object,     *moving.model,     *fixed.object, *fixed.model,
                         X_FW * moving.X_WO, UnitAlong(step_F), tolerance,     {}};
  // Buffers reused: a steady stream of queries allocates nothing once they
  // are large enough.
  FirstTouchBuffers& buffers = Scratch<FirstTouchBuffers>();
  std::vector<TrianglePair>& swept = buffers.swept;
  LocatedContacts& located = buffers.located;
  swept.clear();
  // The step is swept in pieces from its start, and the first piece that
  // touches holds the first touch. A proxy resting on a surface touches it
  // early in its step, and a short piece's swept volume meets few faces.
  constexpr double kPieceEnds[] = {1.0 / 1024, 1.0 / 16, 1.0};
  const Isometry3d X_FM_end = context.X_FM;
  double piece_start = 0;
  std::optional<double> touch_time;
  for (const double piece_end : kPieceEnds) {
    const Vector3d piece_F = (piece_end - piece_start) * step_F;
    context.X_FM = X_FM_end;
    context.X_FM.pretranslate(-(1 - piece_end) * step_F);
    if (const std::optional<double> back = LatestTouchBack(context, piece_F, swept)) {
      context.X_FM.pretranslate(-*back * piece_F);
      touch_time = piece_end - *back * (piece_end - piece_start);
      break;
    }
    piece_start = piece_end;
  }
  if (!touch_time) return false;
  // The swept pairs hold every pair within the tolerance at the touch, and
  // LocateContacts keeps only features within the tolerance: the contacts
  // are those of a pair query there, without its traversal or leaf tests.
  LocateContacts(context, context.X_FM, swept, located);
  touch.time = *touch_time;
  touch.normal_W = fixed.X_WO.linear() * located.normal_F;
  touch.fixed = located.fixed;
  PointsToWorld(located.points, fixed.X_WO, touch.points);
  return true;
}

absl::StatusOr<std::optional<FirstTouch>> FindFirstTouch(const PosedObject& moving,
                                                         const PosedObject& fixed,
                                                         const Vector3d& step_W,
                                                         double relative_tolerance) {
  FirstTouch touch;
  HS_ASSIGN_OR_RETURN(const bool touched,
                      FindFirstTouch(moving, fixed, step_W, relative_tolerance, touch));
  if (!touched) return std::nullopt;
  return touch;
}

absl::Status ComputeContact(const PosedObject& moving, const PosedObject& fixed,
                            const ContactQuery& query, ContactSet& set, PairCache* cache) {
  HS_ASSIGN_OR_RETURN(const double tolerance,
                      PairTolerance(moving, fixed, query.direction_W, query.relative_tolerance));
  if (!(std::isfinite(query.depth_hint_m) && query.depth_hint_m >= 0)) {
    return absl::InvalidArgumentError("depth hint must be finite and >= 0");
  }

  const Isometry3d X_FW = fixed.X_WO.inverse();
  ContactContext context{*moving.object,     *moving.model,    *fixed.object, *fixed.model,
                         X_FW * moving.X_WO, Vector3d::Zero(), tolerance,     {}};
  // Buffers reused: a steady stream of queries allocates nothing once they
  // are large enough. The context's pairs borrow theirs.
  ContactBuffers& buffers = Scratch<ContactBuffers>();
  std::vector<TrianglePair>& pairs = buffers.pairs;
  std::vector<TrianglePair>& swept = buffers.swept;
  ContactSetF& found = buffers.found;
  context.pairs.swap(pairs);
  absl::Cleanup give_back = [&] { context.pairs.swap(pairs); };
  context.pairs.clear();
  swept.clear();
  const Vector3d direction_F = X_FW.linear() * query.direction_W;
  // Shorter than this, the square of the length underflows: no direction.
  const bool no_direction = !(direction_F.squaredNorm() > 1e-300);
  context.pair_cache = cache;
  if (!cache && query.method == ContactMethod::kSweep3d && !query.continuous && !no_direction) {
    context.pair_cache = OwnCache(context, UnitAlong(direction_F), buffers.own_cache);
  }
  FindIntersectingTriangles(*moving.model, context.X_FM, *fixed.model, Isometry3d::Identity(),
                            tolerance, context.pairs, {}, context.pair_cache);
  ClearContactSet(set);
  set.method = query.method;
  set.tolerance_m = tolerance;
  // Continuous: look along the whole step for a first touch.
  double back = 0;  // fraction of the step to move back to the first touch
  std::optional<double> time_of_impact;
  if (query.continuous && !no_direction) {
    if (const std::optional<double> latest = LatestTouchBack(context, direction_F, swept)) {
      back = *latest;
      time_of_impact = 1 - back;
    }
  }
  if (context.pairs.empty() && time_of_impact) {
    // Passed through: reconstruct where it first touched.
    context.X_FM.pretranslate(-back * direction_F);
    MeetingAt(context, swept);
  } else {
    back = 0;
    context.depth_hint_m = query.depth_hint_m;  // taken at this pose
  }
  if (context.pairs.empty()) {
    set.direction_W = no_direction ? Vector3d::Zero() : UnitAlong(query.direction_W);
    return absl::OkStatus();
  }
  context.direction_F = no_direction ? FallbackDirection(context) : UnitAlong(direction_F);
  if (query.method == ContactMethod::kPaper2d) {
    found = ReconstructByProjection(context);
  } else {
    ReconstructBySweep(context, found);
  }
  const double extra = back == 0 ? 0.0 : back * LengthOf(direction_F);
  found.depth_m += extra;
  found.reversing_vector_F -= extra * context.direction_F;
  found.penetrating = found.penetrating || extra > tolerance;
  found.fallback = found.fallback || no_direction;
  ToWorld(found, fixed.X_WO, set);
  set.time_of_impact = time_of_impact;
  return absl::OkStatus();
}

absl::StatusOr<ContactSet> ComputeContact(const PosedObject& moving, const PosedObject& fixed,
                                          const ContactQuery& query) {
  ContactSet set;
  HS_RETURN_IF_ERROR(ComputeContact(moving, fixed, query, set));
  return set;
}

void PointsToWorld(std::span<const ContactPointF> points, const Isometry3d& X_WF,
                   std::vector<ContactPoint>& out) {
  out.clear();
  out.reserve(points.size());
  for (const ContactPointF& p : points) out.push_back({X_WF * p.p_FC, p.moving, p.fixed});
}

void ToWorld(const ContactSetF& found, const Isometry3d& X_WF, ContactSet& set) {
  const Matrix3d R = X_WF.linear();
  set.colliding = found.colliding;
  set.penetrating = found.penetrating;
  set.depth_m = found.depth_m;
  set.direction_W = R * found.direction_F;
  set.reversing_vector_W = R * found.reversing_vector_F;
  set.normal_W = R * found.normal_F;
  set.moving = found.moving;
  set.fixed = found.fixed;
  PointsToWorld(found.points, X_WF, set.points);
  set.singular_case = found.singular_case;
  set.fallback = found.fallback;
  set.plane_depths_m = found.plane_depths_m;
}

}  // namespace hs

#pragma once
// Contact reconstruction for one moving and one fixed object.

#include <optional>

#include "absl/status/statusor.h"
#include "common/collision/collision_model.h"
#include "common/collision/pair_cache.h"
#include "common/contact/contact_set.h"
#include "common/hds/haptic_object.h"

namespace hs {

/// One object as contact reconstruction sees it: its HDS, its hierarchy
/// (built from that HDS and in sync with it), and its pose in the world.
struct PosedObject {
  const HapticObject* object = nullptr;
  const CollisionModel* model = nullptr;
  /// X_WO: object frame to world, metres.
  Isometry3d X_WO = Isometry3d::Identity();
};

/// The smallest object a pair query takes, metres across (its bounding
/// box's diagonal). The contact methods are tested from there up (their
/// ScalesLinearly tests, 1e-9 to 1e6); far below, their products of
/// lengths leave double's range (two cubes 1e-54 m across gave an infinite
/// depth and a NaN reversing vector).
inline constexpr double kMinObjectSizeM = 1e-9;

/// OK when `object` is at least kMinObjectSizeM across, else
/// INVALID_ARGUMENT "is X m across, under the 1e-09 m a contact query
/// takes" (callers name the object). Every query checks it; a scene checks
/// it when built, so that a model too small is refused once, not each step.
absl::Status CheckObjectSize(const HapticObject& object);

struct ContactQuery {
  /// Direction of the moving object's motion relative to the fixed one over
  /// the last step, world frame. Any length (it is normalized); zero makes
  /// the reconstruction estimate one and set ContactSet::fallback.
  Vector3d direction_W = Vector3d::Zero();
  ContactMethod method = ContactMethod::kSweep3d;
  /// Continuous collision: direction_W is then the whole relative motion of
  /// the last step (its length in metres matters), and contact anywhere
  /// along it is found, so a thin object passed through in one step is
  /// caught (paper fig. 3 c) and the time of impact reported.
  bool continuous = false;
  /// Touching tolerance relative to the pair's size (the sum of the two
  /// objects' bounding-box diagonals).
  /// Finite, >= 0, and within what the collision models were built for.
  double relative_tolerance = 1e-9;
  /// A depth along the direction, metres, at which the objects are
  /// expected to be apart (e.g. a haptic tool's distance from its proxy,
  /// which the last step left outside); 0: none. The exact 3D method
  /// searches that far at once instead of in doubling stretches; the answer
  /// is the same whatever the hint. Finite and >= 0.
  double depth_hint_m = 0;
};

/// Reconstructs the contact of `moving` with `fixed` along the query's
/// direction. colliding == false when they neither touch nor penetrate.
/// INVALID_ARGUMENT when a pose or the direction is not finite, a rotation
/// is not orthonormal, the tolerance is out of range, an object is under
/// kMinObjectSizeM across, or the two models do not share a bounding
/// volume type.
absl::StatusOr<ContactSet> ComputeContact(const PosedObject& moving, const PosedObject& fixed,
                                          const ContactQuery& query);
/// The same, written over `set` (every field; its vectors' storage is kept,
/// so that a caller reusing `set` step after step allocates nothing once it
/// is large enough, with the sweep3d method). On error `set` is unspecified.
/// A `cache` kept for this moving and fixed pair between queries lets a
/// query near an earlier one's poses skip most of the pair search
/// (common/collision/pair_cache.h); `set` comes out bit-identical.
absl::Status ComputeContact(const PosedObject& moving, const PosedObject& fixed,
                            const ContactQuery& query, ContactSet& set, PairCache* cache = nullptr);

/// Whether `moving` touches or penetrates `fixed` within the tolerance, or,
/// with `step_W` (the last step's motion, world frame, metres), did so
/// anywhere along that step. The collision-only question: no contact is
/// reconstructed. Errors as ComputeContact.
absl::StatusOr<bool> AreColliding(const PosedObject& moving, const PosedObject& fixed,
                                  double relative_tolerance,
                                  const std::optional<Vector3d>& step_W = std::nullopt);

/// Where a moving object first touches a fixed one along a straight step.
struct FirstTouch {
  /// Fraction of the step, in [0, 1], at the first touch.
  double time = 0;
  /// Unit contact normal at the first touch, world frame, from the fixed
  /// object toward the moving one.
  Vector3d normal_W = Vector3d::Zero();
  /// The fixed object's touched features and the contact points, world
  /// frame, at the first touch.
  SideContact fixed;
  std::vector<ContactPoint> points;
};

/// The first touch of `moving` with `fixed` while `moving` translates by
/// `step_W` (world frame, metres) into its pose `moving.X_WO`; nullopt when
/// they never touch during the step. Cheaper than a continuous
/// ComputeContact: no depth is reconstructed at the end pose. Errors as
/// ComputeContact.
absl::StatusOr<std::optional<FirstTouch>> FindFirstTouch(const PosedObject& moving,
                                                         const PosedObject& fixed,
                                                         const Vector3d& step_W,
                                                         double relative_tolerance);
/// The same, written over `touch` when they touch (true), keeping its
/// vectors' storage; `touch` is unchanged when they do not (false).
absl::StatusOr<bool> FindFirstTouch(const PosedObject& moving, const PosedObject& fixed,
                                    const Vector3d& step_W, double relative_tolerance,
                                    FirstTouch& touch);

}  // namespace hs

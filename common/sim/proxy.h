#pragma once
// The proxy (god-object, Zilles and Salisbury 1995) of a tool: where the
// tool would be if it could not enter the objects. It follows the device
// and stops at the first touch along its path, then slides along the
// surface toward the device (with Coulomb friction when enabled). The path
// is swept exactly (continuous contact), so the proxy never pops through a
// thin object, however far the device moves in one step.

#include <span>

#include "absl/status/statusor.h"
#include "common/contact/contact_query.h"

namespace hs {

struct ProxyOptions {
  double relative_tolerance = 1e-9;
  /// Slide with Coulomb friction from the touched face's material.
  bool friction = false;
  /// Stops and slides per step: each slide ends at the next touch.
  int max_slides = 3;
};

struct ProxyState {
  /// The proxy pose: the device's orientation, the position reached.
  Isometry3d X_WP = Isometry3d::Identity();
  /// Touching an object at the end of the move.
  bool touching = false;
  /// The touched object (index into the obstacles) and face, for materials.
  int obstacle = -1;
  FaceId face = -1;
  /// The tool's own face at the touching point (its material meets the
  /// touched face's when the obstacle is another tool).
  FaceId tool_face = -1;
  /// Unit normal of the last touch, world frame, pointing out of the object.
  Vector3d normal_W = Vector3d::Zero();
  /// A contact point of the last touch, world frame, metres.
  Vector3d p_WC = Vector3d::Zero();
};

/// Moves the proxy of `tool` from `X_WP_before` toward the device pose
/// `X_WD` among `obstacles`. The tool's geometry is `tool.object` and
/// `tool.model`; its pose field is ignored. Errors as ComputeContact.
absl::StatusOr<ProxyState> MoveProxy(const PosedObject& tool, const Isometry3d& X_WP_before,
                                     const Isometry3d& X_WD, std::span<const PosedObject> obstacles,
                                     const ProxyOptions& options);

}  // namespace hs

#pragma once
// Which faces of an object lie near a region: the faces whose bounding
// volumes meet a world box, found down the object's hierarchy; and whether
// any of them rises in front of a plane.

#include <vector>

#include "common/collision/collision_model.h"
#include "common/core/types.h"

namespace hs {

/// Appends to `faces` every face of `model` posed at X_WO (world frame,
/// metres) whose leaf volume meets `box_W` (a world box, metres): every
/// face that meets the box, and some that only come near it (volumes
/// are grown by the model's margin). Degenerate faces are left out. In
/// no particular order.
void FindFacesInBox(const CollisionModel& model, const Isometry3d& X_WO, const AlignedBox3d& box_W,
                    std::vector<FaceId>& faces);

/// Whether a corner of a face of `model` posed at X_WO near `box_W` (world
/// frame, metres: every face that meets the box, and some near it,
/// degenerate faces too) lies more than `slack_m` in front of the plane
/// through `point_W` with unit normal `normal_W`. Volumes with an oriented
/// culling box (OBB, OBBRSS) are opened when they reach in front of the
/// plane and their bounding sphere meets the box; volumes of the other
/// kinds when they meet the box. True for a plane or box with a number
/// that is not finite.
bool AnyCornerInFront(const CollisionModel& model, const Isometry3d& X_WO,
                      const AlignedBox3d& box_W, const Vector3d& point_W, const Vector3d& normal_W,
                      double slack_m);

}  // namespace hs

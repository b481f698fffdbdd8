#pragma once
// Which faces of an object lie near a region: the faces whose bounding
// volumes meet a world box, found down the object's hierarchy.

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

}  // namespace hs

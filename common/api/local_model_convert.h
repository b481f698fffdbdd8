#pragma once
// haptics.v1.LocalModel <-> LocalModel (common/sim/local_model.h). A model
// read from a frame is checked whole before a device's loop may use it.

#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "common/sim/local_model.h"
#include "haptics/v1/session_service.pb.h"

namespace hs {

/// Fills `out` from `model`; `names` gives object names by ObjectId. The
/// surface's faces and tool go with it when `surface_faces`; else its
/// revision, centre and radius alone (for a stream that has its faces).
void LocalModelToProto(const LocalModel& model, const std::vector<std::string>& names,
                       haptics::v1::LocalModel* out, bool surface_faces = true);

/// The model of `model`, its planes' objects unknown (-1). INVALID_ARGUMENT
/// naming the field when a number is not finite or beyond kMaxCoordinate, a
/// normal is not unit (within 1e-6), the radius or clamp is not > 0, a gap
/// is negative, or a material is out of range (stiffness > 0, damping >= 0,
/// 0 <= dynamic friction <= static friction). A surface with faces must
/// hold whole triples, indices within its vertices (no triangle naming a
/// vertex twice), a material for each face, at most kMaxSurfaceTriangles
/// faces, kMaxSurfaceMaterials materials, and a tool hull of at most
/// kMaxToolHullVertices vertices.
absl::StatusOr<LocalModel> LocalModelFromProto(const haptics::v1::LocalModel& model);

}  // namespace hs

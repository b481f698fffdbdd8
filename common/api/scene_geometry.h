#pragma once
// A scene's meshes for viewers (SceneService.GetGeometry): each object's
// HDS vertices, faces and edges in id order, so that the feature ids of a
// frame's contacts index them.

#include <string>
#include <vector>

#include "common/sim/scene.h"
#include "haptics/v1/scene_service.pb.h"

namespace hs {

/// Fills `out` (cleared first) with every object of `scene`, named by
/// `names` (by ObjectId), under scene revision `revision`.
void SceneGeometryToProto(const Scene& scene, const std::vector<std::string>& names,
                          int64_t revision, haptics::v1::SceneGeometry* out);

}  // namespace hs

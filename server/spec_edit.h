#pragma once
// SceneService's changes as edits of a SceneSpec: a change makes a new spec,
// the registry builds a scene from it, and only a scene that builds replaces
// the running one. Validation of values is BuildScene's; these check names.

#include <string>

#include "absl/status/status.h"
#include "haptics/v1/scene_service.pb.h"

namespace hs {

/// Appends `object`. ALREADY_EXISTS when its name is taken.
absl::Status AddObjectToSpec(const haptics::v1::SceneObject& object, haptics::v1::SceneSpec& spec);

/// Applies the pose, materials and vertex moves of `request`. NOT_FOUND
/// for an unknown object.
absl::Status UpdateObjectInSpec(const haptics::v1::UpdateObjectRequest& request,
                                haptics::v1::SceneSpec& spec);

/// Removes object `name`. NOT_FOUND when there is none.
absl::Status RemoveObjectFromSpec(const std::string& name, haptics::v1::SceneSpec& spec);

/// Replaces the allowed effects (empty: all).
void SetEffectsInSpec(const haptics::v1::SetEffectsRequest& request, haptics::v1::SceneSpec& spec);

/// Makes every relative model path absolute against `base_dir`.
void AbsoluteModelPaths(const std::string& base_dir, haptics::v1::SceneSpec& spec);

/// PERMISSION_DENIED when an object names a model file on the server:
/// clients use uploaded models or procedural shapes.
absl::Status RejectModelPaths(const haptics::v1::SceneSpec& spec);

}  // namespace hs

#pragma once
// What the Agones lifecycle reads of a running server: its scene and the
// streams attached to it.

#include "server/agones/agones_lifecycle.h"
#include "server/scene_registry.h"

namespace hs {

/// The game server's scene, `scene` (the first --scene file's), or the
/// first by name when that is "" (a scene created over the API later does
/// not relabel a server that has one), and the devices and viewers over
/// all scenes.
ServerActivity ActivityOf(const SceneRegistry& registry, const std::string& scene);

}  // namespace hs

#pragma once
// What the Agones lifecycle reads of a running server: its scene and the
// streams attached to it.

#include "server/agones/agones_lifecycle.h"
#include "server/scene_registry.h"

namespace hs {

/// The first scene by name (a game server runs one) and the devices and
/// viewers over all scenes.
ServerActivity ActivityOf(const SceneRegistry& registry);

}  // namespace hs

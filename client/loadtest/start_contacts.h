#pragma once
// Whether the load test's tools touch one another where they start: the
// copies of a tool go around world z, and past what the ring holds apart
// (28 copies of the built-in probe) each starts inside its neighbours, so
// every step computes their contacts and the figures measure another
// workload. Asked of the engine itself, on this side, before the run.

#include <string>

#include "haptics/v1/scene.pb.h"

namespace hs::cli {

/// The pairs of `spec`'s tools in contact at their start poses (one step
/// of the scene built here, the tools at rest); -1 when the scene cannot be
/// built here (an uploaded model, a model file not found from `base_dir`).
int ToolPairsTouchingAtStart(const haptics::v1::SceneSpec& spec, const std::string& base_dir);

}  // namespace hs::cli

#pragma once
// What a device asks of its tool's local model with a pose: kept with the
// pose until the step takes it, and in recordings (Scene applies it:
// ApplyLocalModelRequest in scene.h).

namespace hs {

struct LocalModelRequest {
  /// A fresh model at the next step (ToolPose.model_stale).
  bool stale = false;
  /// The validity radius wanted, metres (ToolPose.validity_radius_m; 0:
  /// the scene's).
  double validity_radius_m = 0;
  /// The device reads no planes beside a surface (Open.surface_only).
  bool surface_only = false;
};

}  // namespace hs

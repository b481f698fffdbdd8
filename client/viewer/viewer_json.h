#pragma once
// The viewer page's JSON (docs/viewer.md): a scene's geometry and its
// frames, as the page reads them.

#include <map>
#include <string>

#include "haptics/v1/scene_service.pb.h"
#include "haptics/v1/session_service.pb.h"
#include "nlohmann/json.hpp"

namespace hs::cli {

/// What the bridge adds to a frame for a page.
struct FrameExtras {
  /// How old the frame is as it is sent, milliseconds (from its send time).
  double age_ms = 0;
  /// Steps per second the bridge saw over the last second.
  double step_rate_hz = 0;
  /// Frames this page did not get: the server's drops on the bridge's
  /// stream, and messages replaced before a slow page read them.
  uint64_t dropped_frames = 0;
  /// The scene revision of the geometry the bridge serves.
  int64_t revision = 0;
  /// Tools this bridge's pages hold -> "viewer page N"; the frame names
  /// the holders of the others (ToolState.holder).
  std::map<std::string, std::string> page_holders;
};

/// {"type":"frame", "step", "time_s", "revision", "age_ms", "step_rate_hz",
/// "dropped_frames", "missed_steps", "tools":[...], "bodies":[{"name",
/// "pose", "touching_tools", "held"}]} (bodies as the frame has them:
/// none at a step that did not move them).
nlohmann::json FrameJson(const haptics::v1::Frame& frame, const FrameExtras& extras);

/// {"scene", "revision", "objects":[{"name", "kind", "pose", "vertices",
/// "triangles", "edges", "face_materials", "materials"}]}.
nlohmann::json GeometryJson(const haptics::v1::SceneGeometry& geometry);

}  // namespace hs::cli

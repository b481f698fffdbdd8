#pragma once
// What a viewer page may send over its WebSocket (docs/viewer.md):
// {"type":"take","tool":T}, {"type":"pose","tool":T,"p":[x,y,z],
// "q":[w,x,y,z]}, {"type":"release","tool":T}. Anything else, and any pose
// that is not finite, not rigid or absurdly far, is refused here, at the
// edge, so that it is never forwarded as a pose.

#include <string>
#include <string_view>
#include <variant>

#include "absl/status/statusor.h"
#include "common/core/types.h"

namespace hs::cli {

struct TakeTool {
  std::string tool;
};
struct MoveTool {
  std::string tool;
  Isometry3d X_WD = Isometry3d::Identity();
};
struct ReleaseTool {
  std::string tool;
};
using PageMessage = std::variant<TakeTool, MoveTool, ReleaseTool>;

/// Positions farther than this from the origin are refused, metres.
inline constexpr double kMaxPagePositionM = 1e3;

/// Parses one text message. INVALID_ARGUMENT naming what is wrong: not
/// JSON, an unknown type, a missing or extra field, an empty or over-long
/// tool name, a position not finite or past kMaxPagePositionM, a
/// quaternion not finite or whose norm is not within 1e-3 of 1 (it is
/// normalized).
absl::StatusOr<PageMessage> ParsePageMessage(std::string_view text);

}  // namespace hs::cli

#pragma once
// The scene `hapticctl loadtest` creates, and its devices' paths: copies
// of one tool, turned about world z or in pairs that meet.

#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "client/device_path.h"
#include "haptics/v1/scene.pb.h"

namespace hs::cli {

/// The built-in demo scene (one tool "probe").
haptics::v1::SceneSpec BuiltInLoadScene();

/// How far apart the two tools of a pair start, centre to centre, metres:
/// tools up to about 5 cm across start apart.
inline constexpr double kMeetGapM = 0.06;

/// The scene the test creates: `base`'s fixed objects and `clients` copies
/// of its first tool named "tool-0".., each turned about world z. With
/// `tools_meet`, tools 2k and 2k+1 are pair k: the pairs turned apart,
/// the two of a pair kMeetGapM apart along the turned world y, centre to
/// centre. INVALID_ARGUMENT when `base` has no tool.
absl::StatusOr<haptics::v1::SceneSpec> LoadtestScene(const haptics::v1::SceneSpec& base,
                                                     int clients, const std::string& name,
                                                     bool tools_meet = false);

/// Each device's path with `tools_meet`: tool i (at `starts[i]`) presses
/// towards its partner's start, once a second, to kMeetPastM past the
/// middle, in step with it, so the pair's paths cross; without a partner
/// (the last of an odd count), the plain press (Motion::kPress). The
/// pairs' phases are spread over the second, as the plain presses' are.
inline constexpr double kMeetPastM = 0.005;
std::vector<std::vector<TimedPose>> MeetingPaths(const std::vector<Isometry3d>& starts,
                                                 double rate_hz, double duration_s);

/// Every device's path in `spec` as LoadtestScene made it (its last
/// `clients` objects are the tools): MeetingPaths with `tools_meet`, else
/// each tool's plain press, device i a phase of i / clients second later.
/// INVALID_ARGUMENT when a tool's pose is invalid.
absl::StatusOr<std::vector<std::vector<TimedPose>>> DevicePaths(const haptics::v1::SceneSpec& spec,
                                                                int clients, bool tools_meet,
                                                                double rate_hz, double duration_s);

}  // namespace hs::cli

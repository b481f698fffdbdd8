#pragma once
// A frame from a server (SessionService) as the scorer reads it
// (common/training/scorer.h): the live way into the same scorer that
// offline and recorded runs go through (common/training/step_scoring.h).

#include <string>

#include "common/training/scorer.h"
#include "haptics/v1/session_service.pb.h"

namespace hs {

/// Which stream a frame came on: only a tool's own Interact stream says
/// when its device made the pose applied (last_pose_device_time_ns); a
/// Watch frame does not, for any tool.
enum class FrameStream { kWatch, kToolsDevice };

/// Tool `tool`'s part of `frame` (an empty frame at its time when the
/// frame lacks it), with the pose's device time on `tool`'s own device
/// stream. Non-finite numbers in the frame are taken as 0.
ScoringFrame ScoringFrameFromProto(const haptics::v1::Frame& frame, const std::string& tool,
                                   FrameStream stream);

}  // namespace hs

#pragma once
// A frame from a server (SessionService) as the scorer reads it
// (common/training/scorer.h): the live way into the same scorer that
// offline and recorded runs go through (common/training/step_scoring.h).

#include <string>

#include "common/training/scorer.h"
#include "haptics/v1/session_service.pb.h"

namespace hs {

/// Tool `tool`'s part of `frame` (an empty frame at its time when the
/// frame lacks it). Non-finite numbers in the frame are taken as 0.
ScoringFrame ScoringFrameFromProto(const haptics::v1::Frame& frame, const std::string& tool);

}  // namespace hs

#pragma once
// A simulation step as the scorer reads it (offline: `hapticctl score
// --path` steps the exercise's scene itself).

#include <string>
#include <vector>

#include "common/sim/step_frame.h"
#include "common/training/scorer.h"

namespace hs {

/// Tool `tool`'s part of `frame` (-1 when the frame lacks it: an empty
/// frame at its time); `names` by ObjectId.
ScoringFrame ScoringFrameFromStep(const StepFrame& frame, ObjectId tool,
                                  const std::vector<std::string>& names);

}  // namespace hs

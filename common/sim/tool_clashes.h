#pragma once
// Counts the tool pairs' clashes step by step from the tools' contacts.

#include <vector>

#include "common/sim/step_frame.h"

namespace hs {

/// Updates `clashes` (every pair that ever touched, by (tool_a, tool_b))
/// with one step of `step_s` seconds: a pair touches when either tool's
/// contacts hold the other or its proxy rests on the other's. Allocates
/// only when a pair first touches.
void CountClashes(const std::vector<ToolFrame>& tools, double step_s,
                  std::vector<ToolClash>& clashes);

}  // namespace hs

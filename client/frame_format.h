#pragma once
// haptics.v1.Frame as hapticctl prints it: one line of text or JSON. Used
// by `drive` and `watch`; and the clash totals `watch` and `loadtest` sum.

#include <cstdint>
#include <ostream>

#include "haptics/v1/session_service.pb.h"

namespace hs::cli {

/// One line: the step, the pose it applied, every tool's holder, contacts
/// and force, the tool pairs touching now, dropped frames; with `json`,
/// the Frame as one line of JSON.
void PrintFrame(const haptics::v1::Frame& frame, bool json, std::ostream& out);

/// Every tool pair's clashes in `frame`, summed: how many began and the
/// simulated seconds they touched, since the scene began.
struct ClashTotals {
  int64_t count = 0;
  double seconds = 0;
};
ClashTotals SumClashes(const haptics::v1::Frame& frame);

}  // namespace hs::cli

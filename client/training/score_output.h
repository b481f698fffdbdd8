#pragma once
// A training run's summary, for people (one line) and as JSON (`hapticctl
// score` and `train`).

#include <ostream>

#include "common/training/scorer.h"
#include "nlohmann/json.hpp"

namespace hs::cli {

/// {"score", "completed", "duration_s", "targets_reached", "targets",
/// "path_length_m", "economy", "max_force_n", "force_limit_exceeded_s",
/// "excess_impulse_ns", "forbidden_contacts", "jerk_rms", "target_results",
/// "forbidden_list"}.
nlohmann::ordered_json SummaryJson(const ScoreSummary& s);

/// One line: score, completion, targets, path, forces, errors, jerk.
void PrintSummary(const ScoreSummary& s, std::ostream& out);

}  // namespace hs::cli

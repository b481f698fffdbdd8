#pragma once
// The report of `hapticctl loadtest` as text for a reader: a table of round
// trips and lines of counts, scene figures, echo and CPU.

#include <ostream>

#include "client/loadtest/load_report.h"

namespace hs::cli {

/// Prints `report` to `out` (three decimals).
void PrintLoadReport(const LoadReport& report, std::ostream& out);

}  // namespace hs::cli

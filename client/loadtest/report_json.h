#pragma once
// The report of `hapticctl loadtest --json`: one JSON object.

#include <string>

#include "client/loadtest/load_report.h"

namespace hs::cli {

/// The report as JSON: settings, round trips (ms) overall, per device and
/// of the echo, frames, drops, missed steps, step time, CPU (the server's
/// also per device).
std::string LoadReportJson(const LoadReport& report);

}  // namespace hs::cli

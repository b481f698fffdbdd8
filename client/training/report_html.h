#pragma once
// A training run's report.html (report.h) as text, for people: every
// figure rounded and with its unit, the date in UTC, names as they are
// (HTML-escaped), and the plots inline.

#include <chrono>
#include <string>
#include <vector>

#include "client/training/report.h"

namespace hs::cli {

/// "2026-11-27 14:03 UTC".
std::string UtcMinute(std::chrono::system_clock::time_point at);

/// The report's page, written at `written`, with the PNG files `pngs`
/// inline (base64), in order.
std::string ReportHtml(const ReportInput& input, std::chrono::system_clock::time_point written,
                       const std::vector<std::string>& pngs);

}  // namespace hs::cli

#pragma once
// Running one kind of the load test's streams together, each on its own
// thread, with a progress line once a second.

#include <cstdint>
#include <functional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "client/loadtest/round_trips.h"

namespace hs::cli {

/// "loadtest: PHASE E/D s, N streams, S sent, A answered": `elapsed_s`
/// whole seconds of `duration_s`, and the streams' messages summed.
std::string ProgressLine(std::string_view phase, double elapsed_s, double duration_s,
                         const std::vector<const RoundTrips*>& trips);

/// Runs every one of `runs` on its own thread until all have returned.
/// While they run, a ProgressLine of `trips` (the streams' round trips) on
/// `progress` once a second, when it is not null.
void RunStreams(const std::vector<std::function<void()>>& runs,
                const std::vector<const RoundTrips*>& trips, std::string_view phase,
                double duration_s, std::ostream* progress);

}  // namespace hs::cli

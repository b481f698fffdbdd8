#pragma once
// The load generator of `hapticctl loadtest`: N device streams at a fixed
// rate into one scene (each its own tool), optional viewers, and in the
// same run a bare gRPC echo baseline with messages of the same sizes,
// taking turns with the devices in half-second slices (send_schedule.h).
// Round trip: a pose sent -> the first frame whose last applied pose
// sequence is >= that pose's sequence (the echo: a message sent -> its
// answer). All bounded in count and time. This file wires the units:
// loadtest_options.h (what is asked), loadtest_scene.h (scene and paths),
// device_stream.h, echo_stream.h, viewer_stream.h (the streams),
// stream_runner.h, turn_cpu.h and server_cpu.h (running and CPU),
// load_report.h (the figures).

#include "absl/status/statusor.h"
#include "client/loadtest/load_report.h"
#include "client/loadtest/loadtest_options.h"
#include "client/loadtest/loadtest_scene.h"

namespace hs::cli {

/// Runs the load test (after CheckLoadtestOptions): creates the scene (named "loadtest-PID"),
/// drives it beside the echo baseline, deletes it. INVALID_ARGUMENT for options past the bounds or
/// a remote server without allow_remote; a server's status (its code, "server: " and its message)
/// when a request or stream fails.
absl::StatusOr<LoadReport> RunLoadtest(const LoadtestOptions& options);

}  // namespace hs::cli

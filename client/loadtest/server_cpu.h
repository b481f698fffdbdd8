#pragma once
// Where `hapticctl loadtest` reads the server's CPU time: its Prometheus
// endpoint's process_cpu_seconds_total when one is given, else
// /proc/PID/stat of a process on this machine (a given pid, or the one
// listening on the server's loopback port).

#include <functional>
#include <optional>
#include <string>

#include "client/loadtest/loadtest_options.h"

namespace hs::cli {

/// The name of the CPU counter the Prometheus client libraries export.
inline constexpr char kProcessCpuMetric[] = "process_cpu_seconds_total";

struct ServerCpuSource {
  /// The server's cumulative CPU seconds now; nullopt when it cannot be read.
  std::function<std::optional<double>()> read;
  /// Where they come from ("/proc/PID/stat", "process_cpu_seconds_total at
  /// URL"), or why they are unknown.
  std::string description;
};

/// The source for `options`: server_metrics_url when set (each reading a
/// GET within the connection timeout, capped at 1 s); else server_pid, or
/// the process listening on the loopback port of options.server.address;
/// else none (every reading nullopt).
ServerCpuSource FindServerCpuSource(const LoadtestOptions& options);

}  // namespace hs::cli

#include "client/loadtest/server_cpu.h"

#include <unistd.h>

#include <algorithm>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "client/loadtest/metrics_scrape.h"
#include "client/loadtest/process_cpu.h"
#include "client/loadtest/prometheus_text.h"
#include "common/net/address.h"

namespace hs::cli {
namespace {

// The pid of the process listening on `address`'s port; 0 when none is
// found or the address is not on loopback.
int LoopbackServerPid(const std::string& address) {
  if (!IsLoopbackAddress(address)) return 0;
  const size_t colon = address.rfind(':');
  int port = 0;
  if (colon == std::string::npos || !absl::SimpleAtoi(address.substr(colon + 1), &port)) return 0;
  return FindListeningPid(port).value_or(0);
}

}  // namespace

ServerCpuSource FindServerCpuSource(const LoadtestOptions& options) {
  if (!options.server_metrics_url.empty()) {
    // A reading falls between two slices: it must not hold up the sampling.
    const double timeout_s = std::min(1.0, options.server.timeout_s);
    return {[url = options.server_metrics_url, timeout_s]() -> std::optional<double> {
              absl::StatusOr<std::string> text = FetchMetricsText(url, timeout_s);
              if (!text.ok()) return std::nullopt;
              absl::StatusOr<double> seconds = PrometheusValue(*text, kProcessCpuMetric);
              if (!seconds.ok()) return std::nullopt;
              return *seconds;
            },
            absl::StrCat(kProcessCpuMetric, " at ", options.server_metrics_url)};
  }
  const int pid =
      options.server_pid != 0 ? options.server_pid : LoopbackServerPid(options.server.address);
  if (pid == 0) {
    return {[] { return std::nullopt; },
            "no server process found: give --server-pid or --server-metrics for a server not "
            "on loopback"};
  }
  return {[pid] { return ProcessCpuSeconds(pid); },
          absl::StrCat("/proc/", pid, "/stat",
                       pid == getpid() ? " (this process: server and load generator)" : "")};
}

}  // namespace hs::cli

#pragma once
// Reading a server's Prometheus endpoint over HTTP (libcurl), for the
// server CPU figure of `hapticctl loadtest` when the server runs elsewhere
// or its process cannot be seen.

#include <string>

#include "absl/status/statusor.h"

namespace hs::cli {

/// INVALID_ARGUMENT naming --server-metrics unless `url` is
/// "http://HOST:PORT/PATH" with a port 1..65535.
absl::Status CheckMetricsUrl(const std::string& url);

/// The body of GET `url` (a text exposition). UNAVAILABLE naming the url
/// when it cannot be reached within `timeout_s` or answers other than 200.
absl::StatusOr<std::string> FetchMetricsText(const std::string& url, double timeout_s);

}  // namespace hs::cli

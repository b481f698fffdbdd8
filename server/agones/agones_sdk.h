#pragma once
// The Agones SDK's local REST endpoint (http://localhost:AGONES_SDK_HTTP_PORT),
// through libcurl: the calls a game server makes about its own lifecycle.
// Agones runs the SDK server as a sidecar of the game server's pod.

#include <string>
#include <string_view>

#include "absl/status/status.h"

namespace hs {

class AgonesSdk {
 public:
  /// Talks to 127.0.0.1:`port`; each request gives up after `timeout_s`.
  explicit AgonesSdk(int port, double timeout_s = 1.0);

  /// POST /ready: the server listens and its scene is loaded.
  absl::Status Ready();
  /// POST /health: a health ping (Agones marks the game server Unhealthy
  /// when they stop coming).
  absl::Status Health();
  /// PUT /metadata/label: sets label `key` (Agones prefixes it with
  /// "agones.dev/sdk-") to `value`, which must be a label value
  /// (AgonesLabelValue).
  absl::Status SetLabel(std::string_view key, std::string_view value);
  /// POST /allocate: marks the game server Allocated.
  absl::Status Allocate();
  /// POST /shutdown: asks Agones to shut the game server down (it then
  /// sends SIGTERM).
  absl::Status Shutdown();

 private:
  // UNAVAILABLE naming the call when the endpoint cannot be reached, times
  // out, or answers other than 2xx.
  absl::Status Request(const char* method, const char* path, const std::string& body);

  const std::string base_url_;
  const long timeout_ms_;
};

/// `text` as a Kubernetes label value: lower case, each run of characters
/// other than [a-z0-9._-] made one '-', at most 63 characters, starting
/// and ending with a letter or digit ("probe on torus" -> "probe-on-torus").
/// "" when nothing is left.
std::string AgonesLabelValue(std::string_view text);

}  // namespace hs

#pragma once
// A game server's lifecycle on Agones, from a thread of its own: Ready once
// the server listens with its scene, health pings on an interval, the
// scene's name as a label, Allocated when the first device joins, and a
// request to shut down once the last client has left and an idle time has
// passed. A failed request never affects the server's clients: it is
// logged once, counted (hs_agones_sdk_requests_total, hs_agones_sdk_up)
// and retried.

#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <optional>
#include <ostream>
#include <string>
#include <thread>

#include "server/agones/agones_sdk.h"
#include "server/metrics.h"

namespace hs {

struct AgonesOptions {
  /// The SDK's REST port (AGONES_SDK_HTTP_PORT).
  int sdk_port = 0;
  /// Seconds between health pings; the Fleet's health period must hold
  /// several.
  double health_interval_s = 2;
  /// Seconds without any client, after the last has left, before the
  /// server asks to be shut down.
  double idle_shutdown_s = 60;
  /// How often the server's clients are looked at, seconds.
  double poll_s = 0.05;
};

/// What the lifecycle reads of the server at each poll.
struct ServerActivity {
  /// The scene the game server runs ("" while it has none).
  std::string scene;
  int devices = 0;
  int viewers = 0;
  /// How many ever attached: a client that came and went between two
  /// polls counts.
  int64_t devices_joined = 0;
  int64_t viewers_joined = 0;
};

class AgonesLifecycle {
 public:
  /// Starts the thread; the server listens and has loaded its scenes.
  /// `activity` is called from the thread; `metrics` and `log` outlive
  /// the lifecycle.
  AgonesLifecycle(const AgonesOptions& options, std::function<ServerActivity()> activity,
                  Metrics& metrics, std::ostream& log);
  /// Ends the thread (SIGTERM's drain is the server's).
  ~AgonesLifecycle();
  AgonesLifecycle(const AgonesLifecycle&) = delete;
  AgonesLifecycle& operator=(const AgonesLifecycle&) = delete;

 private:
  using Clock = std::chrono::steady_clock;

  void Run();
  // One poll: what is due at `now`.
  void Poll(Clock::time_point now);
  // Counts and logs the result of `call`; true when it was answered. A
  // failed request other than a health ping puts off the others for a
  // second (health pings keep their interval).
  bool Answered(const char* call, const absl::Status& status, Clock::time_point now);

  const AgonesOptions options_;
  const std::function<ServerActivity()> activity_;
  Metrics& metrics_;
  std::ostream& log_;
  AgonesSdk sdk_;

  // The thread's own state.
  bool ready_ = false;
  std::string label_;
  bool allocated_ = false;
  int64_t clients_joined_ = 0;  // at the last poll
  bool shutdown_requested_ = false;
  bool sdk_failing_ = false;
  std::optional<Clock::time_point> idle_since_;
  Clock::time_point next_health_{};
  Clock::time_point retry_at_{};

  std::mutex mu_;
  std::condition_variable cv_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace hs

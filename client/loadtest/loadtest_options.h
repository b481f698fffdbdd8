#pragma once
// What `hapticctl loadtest` is asked to do, and its bounds.

#include <optional>
#include <ostream>
#include <string>

#include "absl/status/status.h"
#include "client/server_call.h"
#include "common/sim/effects.h"
#include "haptics/v1/scene.pb.h"

namespace hs::cli {

/// Bounds of a load test, checked before it starts.
inline constexpr int kMaxLoadClients = 64;
inline constexpr int kMaxLoadViewers = 16;
inline constexpr double kMaxLoadSeconds = 60;
inline constexpr double kMaxLoadRateHz = 10000;

struct LoadtestOptions {
  ConnectionOptions server;
  /// Device streams, each driving its own tool.
  int clients = 8;
  /// Poses per second per device.
  double rate_hz = 1000;
  /// Frames a second each device asks the server for (frame_rate_args.h);
  /// 0: the server's own rate.
  double frame_rate_hz = 0;
  /// Seconds of load per kind: with the echo baseline the two take turns,
  /// so the run lasts twice as long.
  double duration_s = 10;
  /// The scene: its fixed objects, and its first tool copied once per
  /// client, copy i turned by i * 360 / clients degrees about the world z
  /// axis. Unset: the built-in demo (a ~9,200-triangle torus on a table, a
  /// 2 cm cube probe above the ring), as scenes/probe_on_torus.textproto.
  std::optional<haptics::v1::SceneSpec> scene;
  /// The folder of `scene`'s file: its relative model paths are read from
  /// there to see whether its tools touch at the start (start_contacts.h).
  std::string scene_dir;
  /// The scene's step length, seconds, in [1e-4, 1] (1e-4: 10 kHz);
  /// 0: the scene's own.
  double step_s = 0;
  /// Watch streams (all parts).
  int viewers = 0;
  /// Servers off this machine's loopback are refused unless set.
  bool allow_remote = false;
  /// The server's process id for its CPU figure; 0: the process listening
  /// on the server's port when it is on loopback.
  int server_pid = 0;
  /// The server's Prometheus endpoint, "http://HOST:PORT/metrics": its CPU
  /// figure comes from its process_cpu_seconds_total there instead of
  /// /proc. Empty: /proc.
  std::string server_metrics_url;
  /// Run the echo baseline.
  bool echo = true;
  /// Devices in pairs whose paths cross (LoadtestScene, MeetingPaths):
  /// tool-tool contact in every press.
  bool tools_meet = false;
  /// With the local model among the needs, devices read its planes beside
  /// its surface (as the SDK's devices before 1.3 did), so the server
  /// searches faces for them; else the surface alone, as the SDK's device.
  bool planes = false;
  /// What each device needs; a haptic device needs its force (with friction).
  EffectSet needs = EffectSet::Default();
  /// Where a progress line goes once a second (none when null).
  std::ostream* progress = nullptr;
};

/// INVALID_ARGUMENT naming the option for options past the bounds, a
/// remote server without allow_remote, or a metrics address that is not
/// "http://HOST:PORT/...".
absl::Status CheckLoadtestOptions(const LoadtestOptions& options);

}  // namespace hs::cli

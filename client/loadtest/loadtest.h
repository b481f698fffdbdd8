#pragma once
// The load generator of `hapticctl loadtest`: N device streams at a fixed
// rate into one scene (each its own tool), optional viewers, and in the
// same run a bare gRPC echo baseline with messages of the same sizes,
// taking turns with the devices in half-second slices (send_schedule.h).
// Round trip: a pose sent -> the first frame whose last applied pose
// sequence is >= that pose's sequence (the echo: a message sent -> its
// answer). All bounded in count and time.

#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "common/sim/effects.h"

#include "absl/status/statusor.h"
#include "client/device_path.h"
#include "client/percentiles.h"
#include "client/server_call.h"
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
  /// Seconds of load per kind: with the echo baseline the two take turns,
  /// so the run lasts twice as long.
  double duration_s = 10;
  /// The scene: its fixed objects, and its first tool copied once per
  /// client, copy i turned by i * 360 / clients degrees about the world z
  /// axis. Unset: the built-in demo (a ~9,200-triangle torus on a table, a
  /// 2 cm cube probe above the ring), as scenes/probe_on_torus.textproto.
  std::optional<haptics::v1::SceneSpec> scene;
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
  /// Run the echo baseline.
  bool echo = true;
  /// Devices in pairs whose paths cross (LoadtestScene, MeetingPaths):
  /// tool-tool contact in every press.
  bool tools_meet = false;
  /// What each device needs; a haptic device needs its force (with friction).
  EffectSet needs = EffectSet::Default();
  /// Where a progress line goes once a second (none when null).
  std::ostream* progress = nullptr;
};

/// What one stream (or all of a kind, summed) saw in the measuring window.
struct StreamReport {
  /// Round trips, milliseconds.
  Percentiles rtt_ms;
  int64_t sent = 0;
  /// Sent messages with a round trip (the rest got no answer in time).
  int64_t answered = 0;
  /// Frames received.
  int64_t frames = 0;
  /// Step ids of the first and last frame received.
  int64_t first_step = 0;
  int64_t last_step = 0;
  /// Frames the server dropped for this stream (from the frames' counters).
  int64_t dropped_frames = 0;
  /// Steps the scene missed, and those of them with its stepping thread
  /// off the CPU (Frame.missed_steps_off_cpu), from the frames' counters.
  int64_t missed_steps = 0;
  int64_t missed_steps_off_cpu = 0;
  double frames_per_s = 0;
  /// The scene's tool pairs' clashes begun in the window, and the time
  /// they touched, simulated seconds (Frame.clashes, every pair summed).
  int64_t tool_clashes = 0;
  double tool_clash_s = 0;
};

struct LoadReport {
  std::string scene;
  int64_t triangles = 0;
  int clients = 0;
  int viewers = 0;
  double rate_hz = 0;
  double duration_s = 0;
  /// The scene's step length, seconds.
  double step_s = 0;
  /// What each device asked the scene for.
  EffectSet needs;
  bool tools_meet = false;
  double load_average_1m = -1;
  /// Device streams: overall (round trips pooled, counts summed) and each.
  StreamReport devices;
  std::vector<StreamReport> per_device;
  /// Viewers, counts summed.
  StreamReport viewers_total;
  /// Echo streams, as many as devices at the same rate, pooled; their
  /// frames_per_s is over the echo's turns. Requests as large as a pose
  /// message; answers as large as the devices' latest frames (the mean of
  /// what was asked is echo_reply_bytes).
  bool echo_run = false;
  StreamReport echo;
  int64_t echo_request_bytes = 0;
  int64_t echo_reply_bytes = 0;
  /// The scene's step wall time (server timings of device 0's frames that
  /// applied a new pose of it), ms.
  Percentiles step_ms;
  /// Steps the scene ran and missed in the window (device 0's view).
  int64_t steps = 0;
  int64_t missed_steps = 0;
  /// Of missed_steps, those with the stepping thread off the CPU.
  int64_t missed_steps_off_cpu = 0;
  /// Tool clashes begun in the window and their time (device 0's view).
  int64_t tool_clashes = 0;
  double tool_clash_s = 0;
  /// missed / (run + missed).
  double missed_fraction = 0;
  /// devices.rtt_ms.p99 / echo.rtt_ms.p99 (0 without echo).
  double p99_ratio = 0;
  /// 1.5 x echo p99 + step p99, ms: the round-trip budget of issue 6.
  double p99_budget_ms = 0;
  /// Server CPU, % of one core over the devices' turns; -1 when unknown.
  double server_cpu_percent = -1;
  /// Where server_cpu_percent comes from.
  std::string server_cpu_source;
  /// hapticctl's own CPU (its streams, and the echo server in the echo's
  /// turns), % of one core, over the devices' turns and the echo's.
  double client_cpu_percent = 0;
  double echo_phase_cpu_percent = 0;
  /// CPU the hypervisor took from this machine over the run (MachineStealSeconds),
  /// ms summed over its cores; -1 when unknown. Missed steps follow it.
  double machine_steal_ms = -1;
};

/// INVALID_ARGUMENT naming the option for options past the bounds or a
/// remote server without allow_remote.
absl::Status CheckLoadtestOptions(const LoadtestOptions& options);

/// Runs the load test (after CheckLoadtestOptions): creates the scene (named "loadtest-PID"),
/// drives it beside the echo baseline, deletes it. INVALID_ARGUMENT for options past the bounds or
/// a remote server without allow_remote; a server's status (its code, "server: " and its message)
/// when a request or stream fails.
absl::StatusOr<LoadReport> RunLoadtest(const LoadtestOptions& options);

/// The scene the test creates: `base`'s fixed objects and `clients` copies
/// of its first tool named "tool-0".., each turned about world z. With
/// `tools_meet`, tools 2k and 2k+1 are pair k: the pairs turned apart,
/// the two of a pair kMeetGapM apart along the turned world y, centre to
/// centre. INVALID_ARGUMENT when `base` has no tool.
absl::StatusOr<haptics::v1::SceneSpec> LoadtestScene(const haptics::v1::SceneSpec& base,
                                                     int clients, const std::string& name,
                                                     bool tools_meet = false);

/// How far apart the two tools of a pair start, centre to centre, metres:
/// tools up to about 5 cm across start apart.
inline constexpr double kMeetGapM = 0.06;

/// Each device's path with `tools_meet`: tool i (at `starts[i]`) presses
/// towards its partner's start, once a second, to kMeetPastM past the
/// middle, in step with it, so the pair's paths cross; without a partner
/// (the last of an odd count), the plain press (Motion::kPress). The
/// pairs' phases are spread over the second, as the plain presses' are.
inline constexpr double kMeetPastM = 0.005;
std::vector<std::vector<TimedPose>> MeetingPaths(const std::vector<Isometry3d>& starts,
                                                 double rate_hz, double duration_s);

/// The built-in demo scene (one tool "probe").
haptics::v1::SceneSpec BuiltInLoadScene();

}  // namespace hs::cli

#pragma once
// The report of `hapticctl loadtest`, and how the streams' own reports add
// up into it: counts summed, round trips pooled, the scene's figures from
// device 0's view, CPU split by whose turn it was.

#include <cstdint>
#include <string>
#include <vector>

#include "client/loadtest/turn_cpu.h"
#include "client/percentiles.h"
#include "common/sim/effects.h"

namespace hs::cli {

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
  /// Whether devices read the local model's planes (LoadtestOptions).
  bool planes = false;
  bool tools_meet = false;
  /// Tool pairs in contact where they start (start_contacts.h); -1 when
  /// not known.
  int tools_touching_at_start = -1;
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
  /// server_cpu_percent / clients; -1 when unknown.
  double server_cpu_percent_per_device = -1;
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

/// The streams of one kind as one: counts summed, missed steps the most
/// any saw (they share the scene), steps of the first stream, frames_per_s
/// over `window_s`, and the percentiles of `pooled_rtt_ms` (sorted in
/// place), every stream's round trips together.
StreamReport Pool(const std::vector<StreamReport>& each, std::vector<double>& pooled_rtt_ms,
                  double window_s);

/// Sets the devices' figures of `report` from each device's report
/// (non-empty): per_device; devices pooled from `pooled_rtt_ms`; and the
/// scene's from device 0's view: its step times `step_ms` (sorted in
/// place), steps run and missed, clashes, the missed fraction.
void SetDeviceFigures(std::vector<StreamReport> each, std::vector<double>& pooled_rtt_ms,
                      std::vector<double>& step_ms, double window_s, LoadReport& report);

/// Sets the echo's figures of `report` (after SetDeviceFigures): echo
/// pooled over its turns `window_s`, the mean reply size asked from each
/// stream's mean `reply_bytes`, the p99 ratio devices/echo and the budget
/// 1.5 x echo p99 + step p99.
void SetEchoFigures(const std::vector<StreamReport>& each, std::vector<double>& pooled_rtt_ms,
                    const std::vector<int64_t>& reply_bytes, double window_s, LoadReport& report);

/// Sets the CPU figures of `report` (its clients set) from the turns'
/// totals, in % of one core: the server's over the devices' turns (and
/// per device) with `server_source` saying where it was read, or -1 and
/// "unknown (...)" when it was not; hapticctl's over each kind's turns
/// (the echo's when `echo_run`).
void SetCpuFigures(const TurnTotals& cpu, const std::string& server_source, bool echo_run,
                   LoadReport& report);

}  // namespace hs::cli

#include "client/loadtest/loadtest_command.h"

#include <iomanip>
#include <iostream>

#include "client/exit_codes.h"
#include "client/needs_args.h"
#include "common/api/scene_file.h"
#include "nlohmann/json.hpp"

namespace hs::cli {
namespace {

nlohmann::ordered_json PercentilesJson(const Percentiles& p) {
  return {{"count", p.count}, {"mean", p.mean},  {"p50", p.p50},
          {"p99", p.p99},     {"p99_9", p.p999}, {"max", p.max}};
}

nlohmann::ordered_json StreamJson(const StreamReport& r) {
  return {{"rtt_ms", PercentilesJson(r.rtt_ms)},
          {"sent", r.sent},
          {"answered", r.answered},
          {"frames", r.frames},
          {"frames_per_s", r.frames_per_s},
          {"first_step", r.first_step},
          {"last_step", r.last_step},
          {"dropped_frames", r.dropped_frames},
          {"missed_steps", r.missed_steps},
          {"missed_steps_off_cpu", r.missed_steps_off_cpu},
          {"tool_clashes", r.tool_clashes},
          {"tool_clash_s", r.tool_clash_s}};
}

void PrintRow(const std::string& name, const StreamReport& r, std::ostream& out) {
  const Percentiles& p = r.rtt_ms;
  out << "  " << std::left << std::setw(12) << name << std::right << std::setw(9) << p.count
      << std::setw(9) << p.p50 << std::setw(9) << p.p99 << std::setw(9) << p.p999 << std::setw(9)
      << p.max << std::setw(10) << r.frames_per_s << std::setw(9) << r.dropped_frames << "\n";
}

void PrintReport(const LoadReport& r, std::ostream& out) {
  out << std::fixed << std::setprecision(3);
  out << "loadtest: " << r.clients << " device(s) x " << r.rate_hz << " Hz for " << r.duration_s
      << " s, " << r.viewers << " viewer(s), scene '" << r.scene << "' (" << r.triangles
      << " triangles, steps of " << r.step_s * 1e3 << " ms); devices need: " << NeedsNames(r.needs)
      << "; load average " << r.load_average_1m << " at start\n";
  out << "round trip, ms      count      p50      p99    p99.9      max  frames/s  dropped\n";
  PrintRow("devices", r.devices, out);
  for (size_t i = 0; i < r.per_device.size(); ++i) {
    PrintRow("  device " + std::to_string(i), r.per_device[i], out);
  }
  if (r.echo_run) PrintRow("echo", r.echo, out);
  out << "poses: " << r.devices.sent << " sent, " << r.devices.answered
      << " answered; frames: " << r.devices.frames << " to devices, " << r.viewers_total.frames
      << " to viewers (" << r.viewers_total.dropped_frames << " dropped)\n";
  out << "scene: " << r.steps << " steps, " << r.missed_steps << " missed ("
      << 100 * r.missed_fraction << "%; " << r.missed_steps_off_cpu
      << " with the stepping thread off the CPU); step time ms p50 " << r.step_ms.p50 << ", p99 "
      << r.step_ms.p99 << ", max " << r.step_ms.max << "\n";
  out << "tools " << (r.tools_meet ? "meet in pairs" : "apart") << ": " << r.tool_clashes
      << " clashes, touching " << r.tool_clash_s << " s\n";
  if (r.echo_run) {
    out << "echo (turns with the devices): " << r.echo_request_bytes << " B requests, "
        << r.echo_reply_bytes << " B replies; p99 ratio devices/echo " << r.p99_ratio
        << "; budget 1.5 x echo p99 + step p99 = " << r.p99_budget_ms
        << " ms: " << (r.devices.rtt_ms.p99 <= r.p99_budget_ms ? "met" : "not met") << "\n";
  }
  out << "cpu, % of one core: server " << r.server_cpu_percent << " (" << r.server_cpu_source
      << "), hapticctl " << r.client_cpu_percent << " during devices, " << r.echo_phase_cpu_percent
      << " during echo (echo server included)\n";
  if (r.machine_steal_ms >= 0) {
    out << "hypervisor: " << r.machine_steal_ms
        << " ms of CPU taken from this machine in the run\n";
  }
}

}  // namespace

std::string LoadReportJson(const LoadReport& r) {
  nlohmann::ordered_json per_device = nlohmann::ordered_json::array();
  for (const StreamReport& d : r.per_device) per_device.push_back(StreamJson(d));
  nlohmann::ordered_json json = {{"scene", r.scene},
                                 {"triangles", r.triangles},
                                 {"clients", r.clients},
                                 {"viewers", r.viewers},
                                 {"rate_hz", r.rate_hz},
                                 {"step_s", r.step_s},
                                 {"duration_s", r.duration_s},
                                 {"needs", NeedsNames(r.needs)},
                                 {"load_average_1m", r.load_average_1m},
                                 {"devices", StreamJson(r.devices)},
                                 {"per_device", per_device},
                                 {"viewers_total", StreamJson(r.viewers_total)},
                                 {"echo_run", r.echo_run},
                                 {"echo", StreamJson(r.echo)},
                                 {"echo_request_bytes", r.echo_request_bytes},
                                 {"echo_reply_bytes", r.echo_reply_bytes},
                                 {"step_ms", PercentilesJson(r.step_ms)},
                                 {"steps", r.steps},
                                 {"missed_steps", r.missed_steps},
                                 {"missed_steps_off_cpu", r.missed_steps_off_cpu},
                                 {"missed_fraction", r.missed_fraction},
                                 {"tools_meet", r.tools_meet},
                                 {"tool_clashes", r.tool_clashes},
                                 {"tool_clash_s", r.tool_clash_s},
                                 {"p99_ratio", r.p99_ratio},
                                 {"p99_budget_ms", r.p99_budget_ms},
                                 {"server_cpu_percent", r.server_cpu_percent},
                                 {"server_cpu_source", r.server_cpu_source},
                                 {"client_cpu_percent", r.client_cpu_percent},
                                 {"echo_phase_cpu_percent", r.echo_phase_cpu_percent},
                                 {"machine_steal_ms", r.machine_steal_ms}};
  return json.dump();
}

int RunLoadtestCommand(const LoadtestArgs& args, std::ostream& out, std::ostream& err) {
  LoadtestOptions options = args.options;
  absl::StatusOr<EffectSet> needs = ParseNeeds(args.needs);
  if (!needs.ok()) {
    ReportError("loadtest", needs.status(), err);
    return kExitUsage;
  }
  options.needs = *needs;
  if (!args.scene_file.empty()) {
    absl::StatusOr<haptics::v1::SceneSpec> spec = ReadSceneFile(args.scene_file);
    if (!spec.ok()) return ReportError("loadtest", spec.status(), err);
    options.scene = *std::move(spec);
  }
  if (absl::Status s = CheckLoadtestOptions(options); !s.ok()) {
    ReportError("loadtest", s, err);
    return kExitUsage;
  }
  if (options.progress == nullptr) options.progress = &err;
  absl::StatusOr<LoadReport> report = RunLoadtest(options);
  if (!report.ok()) {
    return ReportRpcError("loadtest",
                          grpc::Status(static_cast<grpc::StatusCode>(report.status().code()),
                                       std::string(report.status().message())),
                          err);
  }
  if (args.json) {
    out << LoadReportJson(*report) << "\n";
  } else {
    PrintReport(*report, out);
  }
  return kExitOk;
}

void AddLoadtestCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<LoadtestArgs>();
  LoadtestOptions& o = args->options;
  CLI::App* cmd = app.add_subcommand(
      "loadtest",
      "N device streams into one scene at a rate, beside a bare gRPC echo of the same sizes");
  AddConnectionOptions(*cmd, o.server);
  cmd->add_option("--clients", o.clients, "Device streams, each its own tool (1..64)")
      ->capture_default_str();
  cmd->add_option("--rate", o.rate_hz, "Poses per second per device (1..10000)")
      ->capture_default_str();
  cmd->add_option("--duration", o.duration_s,
                  "Seconds of load, (0, 60]; the echo takes turns with the devices, as long again")
      ->capture_default_str();
  cmd->add_option("--scene", args->scene_file,
                  "Scene file; its first tool is copied per device (default: built-in demo)");
  cmd->add_option("--step-s", o.step_s,
                  "The scene's step, seconds, 0.0001..1 (0.0001: 10 kHz; default: the scene's)");
  cmd->add_option("--viewers", o.viewers, "Watch streams beside the devices (0..16)")
      ->capture_default_str();
  cmd->add_flag("--json", args->json, "The report as one JSON object");
  cmd->add_flag("--allow-remote", o.allow_remote, "Allow a server that is not on loopback");
  cmd->add_option("--server-pid", o.server_pid,
                  "The server's pid for its CPU figure (default: found from its loopback port)");
  cmd->add_flag(
      "--no-echo", [&o](int64_t) { o.echo = false; }, "Skip the echo baseline");
  cmd->add_flag("--tools-meet", o.tools_meet,
                "Devices in pairs whose paths cross: tool-tool contact in every press");
  AddNeedsOption(*cmd, args->needs);
  cmd->callback(
      [args, &exit_code] { exit_code = RunLoadtestCommand(*args, std::cout, std::cerr); });
}

}  // namespace hs::cli

#include "client/loadtest/loadtest_command.h"

#include <filesystem>
#include <iostream>

#include "client/exit_codes.h"
#include "client/frame_rate_args.h"
#include "client/loadtest/report_text.h"
#include "client/needs_args.h"
#include "common/api/scene_file.h"

namespace hs::cli {

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
    options.scene_dir = std::filesystem::path(args.scene_file).parent_path().string();
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
    PrintLoadReport(*report, out);
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
  AddFrameRateOption(*cmd, o.frame_rate_hz);
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
  cmd->add_option("--server-metrics", o.server_metrics_url,
                  "The server's Prometheus endpoint, http://HOST:PORT/metrics: its CPU figure "
                  "from process_cpu_seconds_total there instead of /proc");
  cmd->add_flag(
      "--no-echo", [&o](int64_t) { o.echo = false; }, "Skip the echo baseline");
  cmd->add_flag("--tools-meet", o.tools_meet,
                "Devices in pairs whose paths cross: tool-tool contact in every press");
  cmd->add_flag("--planes", o.planes,
                "With local_model: devices read its planes beside its surface (SDKs before "
                "1.3), which costs the server a face search");
  AddNeedsOption(*cmd, args->needs);
  cmd->callback(
      [args, &exit_code] { exit_code = RunLoadtestCommand(*args, std::cout, std::cerr); });
}

}  // namespace hs::cli

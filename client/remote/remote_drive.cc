#include "client/remote/remote_drive.h"

#include <algorithm>
#include <chrono>
#include <fstream>
#include <thread>

#include "client/exit_codes.h"
#include "client/frame_rate_args.h"
#include "client/remote/shaped_stream.h"
#include "client/sdk/device_impl.h"
#include "client/sdk/grpc_error.h"
#include "client/server_call.h"
#include "haptics/v1/session_service.grpc.pb.h"
#include "nlohmann/json.hpp"

namespace hs::cli {
namespace {

namespace pb = haptics::v1;
using Clock = std::chrono::steady_clock;

// The frames a second asked of the server (RemoteDriveArgs::frame_rate_hz).
double FrameRate(const RemoteDriveArgs& args) {
  if (args.frame_rate_hz > 0) return args.frame_rate_hz;
  return std::clamp(args.run.pose_rate_hz, kMinFrameRateHz, kMaxFrameRateHz);
}

struct RunResult {
  grpc::Status status;
  RemoteSummary summary;
  std::vector<Vector3d> forces, positions;
};

// The loop's counts as the device reports them.
sdk::LoopCounts CountsOf(const haptics::DeviceState& state) {
  return {.beyond_validity_ticks = state.beyond_validity_ticks,
          .rejected_poses = state.rejected_poses,
          .models_rejected = state.models_rejected,
          .models_restarted = state.models_restarted,
          .passivity_ticks = state.passivity_ticks,
          .passivity_dissipated_j = state.passivity_dissipated_j};
}

// One run of `options` for `duration_s`: the hand holds a Device of its
// own, whose streams cross the link of options.link.
RunResult RunOnce(const RemoteDriveArgs& args, const RemoteRunOptions& options,
                  const std::shared_ptr<grpc::Channel>& channel, const Isometry3d& start,
                  std::span<const Vector3d> reference) {
  RemoteRun run(options, start);
  SimulatedLink link(options.link);
  sdk::DeviceConfig config{.scene = args.scene,
                           .tool = args.tool,
                           .options = options.Device(),
                           .open_timeout_s = kLongestWaitForDeviceS,
                           .extra_needs = {pb::EFFECT_CONTACT_SET, pb::EFFECT_REVERSING_VECTOR}};
  config.options.frame_rate_hz = FrameRate(args);
  // The hand's depth and the round trip at each pose the server applied.
  config.on_frame = [&](const pb::Frame& frame, const sdk::FrameRead& read) {
    run.Read(frame, read, args.tool);
  };
  if (!options.link.ideal()) config.open_pipe = link.Opener();
  RunResult result;
  haptics::Result<std::unique_ptr<haptics::Device>> opened = sdk::OpenDevice(channel, config);
  if (!opened.ok()) {
    result.status = sdk::ToGrpc(opened.error());
    return result;
  }
  std::unique_ptr<haptics::Device> device = *std::move(opened);
  const int64_t ticks = static_cast<int64_t>(args.duration_s / options.tick_s);
  const int64_t last_tick = ticks + static_cast<int64_t>(kLongestWaitForDeviceS / options.tick_s);
  const Clock::time_point t0 = Clock::now();
  for (int64_t k = 0; run.ticks_rendered() < ticks && k < last_tick; ++k) {
    const double now_s = static_cast<double>(k) * options.tick_s;
    std::this_thread::sleep_until(
        t0 + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(now_s)));
    run.Feel(now_s, device->Tick(run.DevicePose()));
    if (k % 100 == 0 && device->State().closed) break;
  }
  const haptics::DeviceState state = device->State();
  device.reset();  // ends the stream: the link's figures are final
  if (state.closed) result.status = sdk::ToGrpc(state.last_error);
  result.summary = run.Summary(reference, CountsOf(state), link.Stats());
  result.forces = run.forces();
  result.positions = run.device_positions();
  return result;
}

nlohmann::json SummaryJson(const RemoteDriveArgs& args, const RemoteSummary& s) {
  const LinkConditions& link = args.run.link;
  return {{"mode", args.run.local_model ? "local_model" : "server_force"},
          {"operator", OperatorName(args.run.motion)},
          {"latency_ms", link.latency_ms},
          {"jitter_ms", link.jitter_ms},
          {"loss", link.loss},
          {"stall_prob", link.stall_prob},
          {"stall_ms", link.stall_ms},
          {"seed", link.seed},
          {"pose_rate_hz", args.run.pose_rate_hz},
          {"frame_rate_hz", FrameRate(args)},
          {"ticks", s.ticks},
          {"energy_j", s.energy_j},
          {"max_force_step_n", s.max_force_step_n},
          {"max_force_n", s.max_force_n},
          {"penetration_p99_m", s.penetration_p99_m},
          {"penetration_max_m", s.penetration_max_m},
          {"force_rms_error_n", s.force_rms_error_n},
          {"reference_force_rms_n", s.reference_force_rms_n},
          {"uplink_mean_ms", s.uplink_mean_ms},
          {"downlink_mean_ms", s.downlink_mean_ms},
          {"round_trip_p50_ms", s.round_trip_p50_ms},
          {"round_trip_p99_ms", s.round_trip_p99_ms},
          {"poses_lost", s.poses_lost},
          {"frames_lost", s.frames_lost},
          {"poses_stalled", s.poses_stalled},
          {"frames_stalled", s.frames_stalled},
          {"models_rejected", s.models_rejected},
          {"models_restarted", s.models_restarted},
          {"beyond_validity_ticks", s.beyond_validity_ticks},
          {"passivity_ticks", s.passivity_ticks},
          {"passivity_dissipated_j", s.passivity_dissipated_j}};
}

}  // namespace

int RunRemoteDrive(const RemoteDriveArgs& args, const std::shared_ptr<grpc::Channel>& channel,
                   const std::shared_ptr<grpc::Channel>& reference_channel, const Isometry3d& start,
                   std::ostream& out, std::ostream& err) {
  std::vector<Vector3d> reference;
  if (!args.run.link.ideal() || reference_channel != nullptr) {
    RemoteRunOptions ideal = args.run;
    ideal.link = LinkConditions{.seed = args.run.link.seed};
    RunResult first =
        RunOnce(args, ideal, reference_channel != nullptr ? reference_channel : channel, start, {});
    if (!first.status.ok()) return ReportRpcError("drive", first.status, err);
    reference = std::move(first.forces);
  }
  const RunResult run = RunOnce(args, args.run, channel, start, reference);
  if (!run.status.ok()) return ReportRpcError("drive", run.status, err);
  if (!args.trace_path.empty()) {
    std::ofstream trace(args.trace_path);
    trace << "t_s,fx_n,fy_n,fz_n,x_m,y_m,z_m\n";
    for (size_t i = 0; i < run.forces.size(); ++i) {
      const Vector3d& f = run.forces[i];
      const Vector3d& p = run.positions[i];
      trace << static_cast<double>(i) * args.run.tick_s << ',' << f.x() << ',' << f.y() << ','
            << f.z() << ',' << p.x() << ',' << p.y() << ',' << p.z() << '\n';
    }
    if (!trace) return ReportError("drive", "cannot write " + args.trace_path, err);
  }
  const nlohmann::json summary = SummaryJson(args, run.summary);
  if (args.json) {
    out << summary.dump() << '\n';
  } else {
    for (const auto& [key, value] : summary.items()) out << key << ": " << value << '\n';
  }
  return kExitOk;
}

}  // namespace hs::cli

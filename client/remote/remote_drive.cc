#include "client/remote/remote_drive.h"

#include <algorithm>
#include <chrono>
#include <fstream>
#include <thread>

#include "client/exit_codes.h"
#include "client/frame_rate_args.h"
#include "client/needs_args.h"
#include "client/sdk/interact_stream.h"
#include "client/server_call.h"
#include "common/api/local_model_convert.h"
#include "common/api/proto_convert.h"
#include "haptics/v1/session_service.grpc.pb.h"
#include "nlohmann/json.hpp"

namespace hs::cli {
namespace {

namespace pb = haptics::v1;
using Clock = std::chrono::steady_clock;

// DepthBehindProxy of `tool`'s frame (0 when a pose or normal is not a
// finite one).
double ProxyDepth(const pb::ToolState& tool) {
  const absl::StatusOr<Vector3d> p_WD = VectorFromProto(tool.device_pose().position_m(), "device");
  const absl::StatusOr<Vector3d> p_WP = VectorFromProto(tool.proxy_pose().position_m(), "proxy");
  std::vector<Vector3d> normals;
  for (const pb::Contact& c : tool.contacts()) {
    const absl::StatusOr<Vector3d> n = VectorFromProto(c.normal_w(), "normal");
    if (n.ok()) normals.push_back(*n);
  }
  return p_WD.ok() && p_WP.ok() ? DepthBehindProxy(*p_WD, *p_WP, normals) : 0;
}

// What the device reads from `frame` for `tool`.
ServerFrame ReadFrame(const pb::Frame& frame, const std::string& tool) {
  ServerFrame out;
  out.applied_sequence = frame.last_pose_sequence();
  for (const pb::ToolState& t : frame.tools()) {
    if (t.tool() != tool) continue;
    out.force_W = Vector3d(t.force_w_n().x(), t.force_w_n().y(), t.force_w_n().z());
    if (!out.force_W.allFinite()) out.force_W.setZero();
    if (t.has_local_model()) {
      absl::StatusOr<LocalModel> model = LocalModelFromProto(t.local_model());
      if (model.ok()) {
        out.model = *std::move(model);
      } else {
        out.model_rejected = true;
      }
    }
    out.depth_m = ProxyDepth(t);
  }
  return out;
}

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

// One run of `options` for `duration_s` on its own stream.
RunResult RunOnce(const RemoteDriveArgs& args, const RemoteRunOptions& options,
                  const std::shared_ptr<grpc::Channel>& channel, const Isometry3d& start,
                  std::span<const Vector3d> reference) {
  pb::InteractRequest::Open open;
  open.set_scene(args.scene);
  open.set_tool(args.tool);
  EffectSet needs{Effect::kForce, Effect::kFriction, Effect::kContactSet, Effect::kReversingVector};
  if (options.local_model) needs = needs.With(Effect::kLocalModel);
  SetNeeds(needs, open);
  SetFrameRate(open, FrameRate(args));
  RemoteRun run(options, start);
  const Clock::time_point t0 = Clock::now();
  auto seconds_since_start = [&] {
    return std::chrono::duration<double>(Clock::now() - t0).count();
  };
  sdk::InteractStream stream(
      channel, open,
      {.on_frame =
           [&](const pb::Frame& frame) {
             run.FromServer(seconds_since_start(), ReadFrame(frame, args.tool));
           },
       .on_end = nullptr},
      std::chrono::system_clock::now() + std::chrono::seconds(30) +
          std::chrono::milliseconds(static_cast<int64_t>(args.duration_s * 1e3)));
  const int64_t ticks = static_cast<int64_t>(args.duration_s / options.tick_s);
  bool writing = true;
  const int64_t last_tick = ticks + static_cast<int64_t>(kLongestWaitForDeviceS / options.tick_s);
  for (int64_t k = 0; run.ticks_rendered() < ticks && k < last_tick && writing; ++k) {
    const double now_s = static_cast<double>(k) * options.tick_s;
    std::this_thread::sleep_until(
        t0 + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(now_s)));
    run.Tick(k);
    run.DeliverPoses(now_s, [&](const PoseMessage& pose) {
      pb::InteractRequest request;
      request.mutable_pose()->set_sequence(pose.sequence);
      request.mutable_pose()->set_device_time_ns(static_cast<int64_t>(now_s * 1e9));
      PoseToProto(pose.X_WD, request.mutable_pose()->mutable_pose());
      request.mutable_pose()->set_model_stale(pose.model_stale);
      request.mutable_pose()->set_validity_radius_m(pose.validity_radius_m);
      writing = writing && stream.Write(request);
    });
  }
  stream.WritesDone();
  RunResult result;
  result.status = stream.Finish();
  result.summary = run.Summary(reference);
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

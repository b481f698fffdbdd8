#include "client/drive_command.h"

#include <grpcpp/grpcpp.h>

#include <atomic>
#include <chrono>
#include <iostream>
#include <thread>

#include "client/channel.h"
#include "client/device_path.h"
#include "client/exit_codes.h"
#include "client/frame_format.h"
#include "client/frame_rate_args.h"
#include "client/needs_args.h"
#include "client/remote/remote_drive.h"
#include "client/sdk/interact_stream.h"
#include "common/api/proto_convert.h"
#include "haptics/v1/scene_service.grpc.pb.h"
#include "haptics/v1/session_service.grpc.pb.h"

namespace hs::cli {
namespace {

namespace pb = haptics::v1;
using Clock = std::chrono::steady_clock;

// The tool's pose in the scene's spec, where a built-in motion starts.
grpc::Status ToolStartPose(const DriveArgs& args, std::shared_ptr<grpc::Channel> channel,
                           Isometry3d& X_WT) {
  auto stub = pb::SceneService::NewStub(std::move(channel));
  pb::GetSceneRequest request;
  request.set_scene(args.scene);
  pb::SceneInfo info;
  grpc::Status status = stub->GetScene(ContextWithin(args.server.timeout_s).get(), request, &info);
  if (!status.ok()) return status;
  for (const pb::SceneObject& object : info.spec().objects()) {
    if (object.name() != args.tool) continue;
    absl::StatusOr<Isometry3d> pose = PoseFromProto(object.pose(), "pose");
    if (!pose.ok()) return grpc::Status(grpc::StatusCode::INTERNAL, "the tool's pose is invalid");
    X_WT = *pose;
    return grpc::Status::OK;
  }
  return grpc::Status(grpc::StatusCode::NOT_FOUND,
                      "scene '" + args.scene + "' has no object '" + args.tool + "'");
}

}  // namespace

int RunDrive(const DriveArgs& args, std::ostream& out, std::ostream& err) {
  if (!(args.rate_hz > 0)) return ReportError("drive", "--rate must be > 0", err);
  if (args.frame_rate_hz != 0) {
    if (absl::Status s = CheckFrameRate(args.frame_rate_hz); !s.ok()) {
      ReportError("drive", s, err);
      return kExitUsage;
    }
  }
  if (!(args.passivity_damping_ns_per_m >= 0 && args.passivity_damping_ns_per_m <= 1000)) {
    ReportError("drive", "--passivity-damping must be a number from 0 to 1000", err);
    return kExitUsage;
  }
  if (absl::Status link = CheckLinkConditions(args.link); !link.ok()) {
    ReportError("drive", link, err);
    return kExitUsage;
  }
  absl::StatusOr<EffectSet> needs = ParseNeeds(args.needs);
  if (!needs.ok()) return ReportError("drive", needs.status(), err);
  absl::StatusOr<std::shared_ptr<grpc::Channel>> opened = MakeChannel(args.server);
  if (!opened.ok()) return ReportError("drive", opened.status(), err);
  std::shared_ptr<grpc::Channel> channel = *std::move(opened);
  if (!args.operator_motion.empty()) {
    absl::StatusOr<OperatorMotion> motion = ParseOperator(args.operator_motion);
    if (!motion.ok()) return ReportError("drive", motion.status(), err);
    Isometry3d start;
    if (grpc::Status s = ToolStartPose(args, channel, start); !s.ok()) {
      return ReportRpcError("drive", s, err);
    }
    RemoteDriveArgs remote{.scene = args.scene,
                           .tool = args.tool,
                           .duration_s = args.duration_s,
                           .trace_path = args.trace_path,
                           .json = args.json,
                           .frame_rate_hz = args.frame_rate_hz};
    if (args.rate_given) remote.run.pose_rate_hz = args.rate_hz;
    remote.run.motion = *motion;
    remote.run.local_model = args.local_model == "on";
    remote.run.link = args.link;
    remote.run.max_passivity_damping_ns_per_m = args.passivity_damping_ns_per_m;
    std::shared_ptr<grpc::Channel> reference;
    if (!args.reference_server.empty()) {
      ConnectionOptions direct = args.server;
      direct.address = args.reference_server;
      absl::StatusOr<std::shared_ptr<grpc::Channel>> made = MakeChannel(direct);
      if (!made.ok()) return ReportError("drive", made.status(), err);
      reference = *std::move(made);
    }
    return RunRemoteDrive(remote, channel, reference, start, out, err);
  }
  std::vector<TimedPose> path;
  if (!args.motion.empty()) {
    absl::StatusOr<Motion> motion = ParseMotion(args.motion);
    if (!motion.ok()) return ReportError("drive", motion.status(), err);
    Isometry3d start;
    if (grpc::Status s = ToolStartPose(args, channel, start); !s.ok()) {
      return ReportRpcError("drive", s, err);
    }
    path = MotionPath(*motion, start, args.rate_hz, args.duration_s,
                      {.depth_m = args.depth_m, .amplitude_m = args.amplitude_m});
  } else {
    absl::StatusOr<std::vector<TimedPose>> read = ReadDevicePath(args.path, args.rate_hz);
    if (!read.ok()) return ReportError("drive", read.status(), err);
    path = *std::move(read);
  }

  pb::InteractRequest::Open open;
  open.set_scene(args.scene);
  open.set_tool(args.tool);
  open.set_take_over(args.take_over);
  SetNeeds(*needs, open);
  SetFrameRate(open, args.frame_rate_hz);
  const double last_t_s = path.empty() ? 0 : path.back().t_s;
  const uint64_t last = path.size();
  std::atomic<uint64_t> applied{0};
  uint64_t printed = 0;
  // Frames are printed on the stream's reader thread; this one sends the
  // poses on their schedule.
  sdk::InteractStream stream(channel, open,
                             {.on_frame =
                                  [&](const pb::Frame& frame) {
                                    if (frame.last_pose_sequence() <= printed) return;
                                    printed = frame.last_pose_sequence();
                                    applied.store(printed);
                                    PrintFrame(frame, args.json, out);
                                  },
                              .on_end = [&] { applied.store(last); }},
                             std::chrono::system_clock::now() + std::chrono::seconds(30) +
                                 std::chrono::microseconds(static_cast<int64_t>(last_t_s * 1e6)));
  const Clock::time_point start = Clock::now();
  bool writing = true;
  for (uint64_t i = 0; i < last && writing; ++i) {
    std::this_thread::sleep_until(start + std::chrono::duration_cast<Clock::duration>(
                                              std::chrono::duration<double>(path[i].t_s)));
    pb::InteractRequest request;
    pb::ToolPose* pose = request.mutable_pose();
    pose->set_sequence(i + 1);
    pose->set_device_time_ns(
        std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now().time_since_epoch())
            .count());
    PoseToProto(path[i].X_WD, pose->mutable_pose());
    writing = stream.Write(request);
  }
  // Done once the last pose shows up in a frame (or after a while).
  const Clock::time_point wait_until = Clock::now() + std::chrono::seconds(5);
  while (writing && applied.load() < last && Clock::now() < wait_until) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  stream.WritesDone();
  const grpc::Status status = stream.Finish();
  return status.ok() ? kExitOk : ReportRpcError("drive", status, err);
}

void AddDriveCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<DriveArgs>();
  CLI::App* cmd = app.add_subcommand(
      "drive", "Act as an input device: play a tool path or a motion into a scene on a server");
  AddConnectionOptions(*cmd, args->server);
  cmd->add_option("--scene", args->scene, "Scene name")->required();
  cmd->add_option("--tool", args->tool, "Tool object to drive")->required();
  CLI::Option* path = cmd->add_option(
      "--path", args->path,
      "Device poses: CSV 'x,y,z,rx,ry,rz' lines, or *.jsonl {\"t_s\":T,\"pose\":[...]} lines");
  CLI::Option* motion =
      cmd->add_option("--motion", args->motion, "A built-in motion from the tool's pose")
          ->check(CLI::IsMember({"press", "sweep"}));
  path->excludes(motion);
  motion->excludes(path);
  cmd->add_option("--duration", args->duration_s, "Seconds of --motion")
      ->check(CLI::Range(0.0, 3600.0))
      ->capture_default_str();
  cmd->add_option("--depth", args->depth_m, "How far --motion goes down, metres")
      ->capture_default_str();
  cmd->add_option("--amplitude", args->amplitude_m, "How far a sweep goes each side, metres")
      ->capture_default_str();
  CLI::Option* rate =
      cmd->add_option("--rate", args->rate_hz,
                      "Poses per second (with --operator: default 250, as the SDK's device)")
          ->check(CLI::Range(1e-3, 1e5))
          ->capture_default_str();
  AddFrameRateOption(*cmd, args->frame_rate_hz);
  cmd->add_flag("--json", args->json, "One JSON object (haptics.v1.Frame) per line");
  cmd->add_flag("--take-over", args->take_over,
                "Take the tool from the device holding it, which is ended (needs the admin "
                "role)");
  AddNeedsOption(*cmd, args->needs);
  CLI::Option* hand =
      cmd->add_option("--operator", args->operator_motion,
                      "A simulated hand drives the tool in a closed loop and one summary is "
                      "printed (docs/remote-haptics.md)")
          ->check(CLI::IsMember({"press", "slide", "tap"}));
  hand->excludes(path);
  hand->excludes(motion);
  cmd->add_option("--local-model", args->local_model,
                  "With --operator: render from the local contact model on the device (on) or "
                  "apply the server's forces as they arrive (off)")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  cmd->add_option("--passivity-damping", args->passivity_damping_ns_per_m,
                  "With --operator and the local model: the most damping, N*s/m, the device "
                  "loop adds to take back energy the rendering put into the hand (0: off)")
      ->check(CLI::Range(0.0, 1000.0))
      ->capture_default_str();
  cmd->add_option("--latency-ms", args->link.latency_ms,
                  "With --operator: simulated round trip, milliseconds")
      ->check(CLI::Range(0.0, 1000.0));
  cmd->add_option("--jitter-ms", args->link.jitter_ms,
                  "With --operator: up to this much more each way, milliseconds (uniform)")
      ->check(CLI::Range(0.0, 1000.0));
  cmd->add_option("--loss", args->link.loss,
                  "With --operator: probability each message is lost, each way (as an "
                  "unreliable transport would lose it)")
      ->check(CLI::Range(0.0, 0.5));
  cmd->add_option("--stall-prob", args->link.stall_prob,
                  "With --operator: probability a message is held --stall-ms longer, with "
                  "everything behind it, each way (as a reliable stream holds a lost segment)")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--stall-ms", args->link.stall_ms,
                  "With --operator: how long a stalled message is held, milliseconds")
      ->check(CLI::Range(0.0, kMaxLinkMs));
  cmd->add_option("--seed", args->link.seed, "With --operator: the link's random seed")
      ->capture_default_str();
  cmd->add_option("--trace", args->trace_path,
                  "With --operator: write the rendered force and device position per tick (CSV)");
  cmd->add_option("--reference-server", args->reference_server,
                  "With --operator: run the zero-latency reference (force_rms_error_n) against "
                  "this address, the server itself when --server is a relay");
  cmd->callback([args, path, motion, hand, rate, &exit_code] {
    if (path->count() + motion->count() + hand->count() != 1) {
      std::cerr << "hapticctl drive: give --path, --motion or --operator\n";
      exit_code = kExitUsage;
      return;
    }
    args->rate_given = rate->count() > 0;
    exit_code = RunDrive(*args, std::cout, std::cerr);
  });
}

}  // namespace hs::cli

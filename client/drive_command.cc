#include "client/drive_command.h"

#include <google/protobuf/util/json_util.h>
#include <grpcpp/grpcpp.h>

#include <atomic>
#include <chrono>
#include <iostream>
#include <thread>

#include "absl/strings/str_cat.h"
#include "client/exit_codes.h"
#include "client/tool_path.h"
#include "haptics/v1/session_service.grpc.pb.h"
#include "server/proto_convert.h"

namespace hs::cli {
namespace {

namespace pb = haptics::v1;
using Clock = std::chrono::steady_clock;

std::ostream& operator<<(std::ostream& out, const pb::Vector3& v) {
  return out << "(" << v.x() << ", " << v.y() << ", " << v.z() << ")";
}

void PrintFrame(const pb::Frame& frame, bool json, std::ostream& out) {
  if (json) {
    std::string text;
    google::protobuf::util::JsonPrintOptions options;
    options.preserve_proto_field_names = true;
    (void)google::protobuf::util::MessageToJsonString(frame, &text, options);
    out << text << "\n";
    return;
  }
  out << "step " << frame.step() << " pose " << frame.last_pose_sequence();
  for (const pb::ToolState& tool : frame.tools()) {
    out << "  " << tool.tool() << ": " << tool.contacts_size() << " contact(s)";
    for (const pb::Contact& c : tool.contacts()) {
      out << " [" << c.object() << (c.penetrating() ? " penetrating" : " touching") << ", depth "
          << c.depth_m() << " m, normal " << c.normal_w() << "]";
    }
    out << ", force " << tool.force_w_n() << " N";
  }
  if (frame.dropped_frames() > 0) out << "  (" << frame.dropped_frames() << " frames dropped)";
  out << "\n";
}

}  // namespace

int RunDrive(const DriveArgs& args, std::ostream& out, std::ostream& err) {
  auto fail = [&](const std::string& message) {
    err << "hapticctl drive: " << message << "\n";
    return kExitFailure;
  };
  absl::StatusOr<std::vector<Isometry3d>> path = ReadToolPath(args.path);
  if (!path.ok()) return fail(std::string(path.status().message()));
  if (!(args.rate_hz > 0)) return fail("--rate must be > 0");

  auto stub = pb::SessionService::NewStub(
      grpc::CreateChannel(args.server, grpc::InsecureChannelCredentials()));
  grpc::ClientContext context;
  const auto period = std::chrono::duration<double>(1.0 / args.rate_hz);
  context.set_deadline(
      std::chrono::system_clock::now() + std::chrono::seconds(30) +
      std::chrono::duration_cast<std::chrono::system_clock::duration>(period * path->size()));
  auto stream = stub->Interact(&context);
  pb::InteractRequest open;
  open.mutable_open()->set_scene(args.scene);
  open.mutable_open()->set_tool(args.tool);
  stream->Write(open);

  const uint64_t last = path->size();
  std::atomic<uint64_t> applied{0};
  // Poses go out at the rate on their own thread; this one reads frames.
  std::thread writer([&] {
    const Clock::time_point start = Clock::now();
    for (uint64_t i = 0; i < last; ++i) {
      std::this_thread::sleep_until(start +
                                    std::chrono::duration_cast<Clock::duration>(period * i));
      pb::InteractRequest request;
      pb::ToolPose* pose = request.mutable_pose();
      pose->set_sequence(i + 1);
      pose->set_device_time_ns(
          std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now().time_since_epoch())
              .count());
      PoseToProto((*path)[i], pose->mutable_pose());
      if (!stream->Write(request)) return;
    }
    // Done once the last pose shows up in a frame (or after a while).
    const Clock::time_point wait_until = Clock::now() + std::chrono::seconds(5);
    while (applied.load() < last && Clock::now() < wait_until) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    stream->WritesDone();
  });
  pb::Frame frame;
  uint64_t printed = 0;
  while (stream->Read(&frame)) {
    if (frame.last_pose_sequence() <= printed) continue;
    printed = frame.last_pose_sequence();
    applied.store(printed);
    PrintFrame(frame, args.json, out);
  }
  applied.store(last);
  writer.join();
  const grpc::Status status = stream->Finish();
  if (!status.ok()) {
    return fail(absl::StrCat(
        "server: ", absl::StatusCodeToString(static_cast<absl::StatusCode>(status.error_code())),
        ": ", status.error_message()));
  }
  return kExitOk;
}

void AddDriveCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<DriveArgs>();
  CLI::App* cmd = app.add_subcommand(
      "drive", "Act as an input device: play a tool path into a scene on a server");
  cmd->add_option("--server", args->server, "haptic-server address, host:port")
      ->capture_default_str();
  cmd->add_option("--scene", args->scene, "Scene name")->required();
  cmd->add_option("--tool", args->tool, "Tool object to drive")->required();
  cmd->add_option("--path", args->path, "Device poses, one 'x,y,z,rx,ry,rz' line each")->required();
  cmd->add_option("--rate", args->rate_hz, "Poses per second")
      ->check(CLI::Range(1e-3, 1e5))
      ->capture_default_str();
  cmd->add_flag("--json", args->json, "One JSON object (haptics.v1.Frame) per line");
  cmd->callback([args, &exit_code] { exit_code = RunDrive(*args, std::cout, std::cerr); });
}

}  // namespace hs::cli

#include "client/viewer/page_device.h"

#include <chrono>

#include "client/needs_args.h"
#include "client/server_call.h"
#include "common/api/proto_convert.h"

namespace hs::cli {

namespace pb = haptics::v1;

PageDevice::PageDevice(const std::shared_ptr<grpc::Channel>& channel, const std::string& scene,
                       const std::string& tool, Report report,
                       const std::optional<Isometry3d>& X_WD_now)
    : tool_(tool), stub_(pb::SessionService::NewStub(channel)) {
  stream_ = stub_->Interact(&context_);
  pb::InteractRequest open;
  open.mutable_open()->set_scene(scene);
  open.mutable_open()->set_tool(tool);
  // The page shows what the scene's Watch brings; its own stream needs
  // only the force, the least a device asks.
  SetNeeds(EffectSet{Effect::kForce, Effect::kFriction}, *open.mutable_open());
  stream_->Write(open);
  if (X_WD_now) SendPose(*X_WD_now);
  reader_ = std::thread([this, report = std::move(report)] {
    pb::Frame frame;
    bool held = false;
    while (stream_->Read(&frame)) {
      if (!held) report("held", "");
      held = true;
    }
    const grpc::Status status = stream_->Finish();
    if (held && (status.ok() || status.error_code() == grpc::StatusCode::CANCELLED)) {
      report("released", status.ok() ? "" : status.error_message());
    } else {
      report("refused", StatusCodeName(status.error_code()) + ": " + status.error_message());
    }
  });
}

PageDevice::~PageDevice() {
  stream_->WritesDone();
  context_.TryCancel();
  reader_.join();
}

void PageDevice::SendPose(const Isometry3d& X_WD) {
  pb::InteractRequest request;
  pb::ToolPose* pose = request.mutable_pose();
  pose->set_sequence(++sequence_);
  pose->set_device_time_ns(std::chrono::duration_cast<std::chrono::nanoseconds>(
                               std::chrono::steady_clock::now().time_since_epoch())
                               .count());
  PoseToProto(X_WD, pose->mutable_pose());
  stream_->Write(request);
  last_pose_ = X_WD;
  last_sent_ = std::chrono::steady_clock::now();
}

void PageDevice::KeepAlive(std::chrono::steady_clock::duration idle) {
  if (last_pose_ && std::chrono::steady_clock::now() - last_sent_ >= idle) SendPose(*last_pose_);
}

}  // namespace hs::cli

#include "client/loadtest/device_stream.h"

#include <algorithm>
#include <thread>

#include "client/frame_rate_args.h"
#include "client/needs_args.h"
#include "common/api/proto_convert.h"

namespace hs::cli {

namespace pb = haptics::v1;

pb::InteractRequest OpenRequest(const DeviceOpen& open) {
  pb::InteractRequest request;
  pb::InteractRequest::Open& first = *request.mutable_open();
  first.set_scene(open.scene);
  first.set_tool(open.tool);
  SetNeeds(open.needs, first);
  SetFrameRate(first, open.frame_rate_hz);
  first.set_surface_only(open.surface_only);
  return request;
}

DeviceStream::DeviceStream(pb::SessionService::Stub& stub, const DeviceOpen& open,
                           std::vector<TimedPose> path, std::atomic<int64_t>& frame_bytes)
    : path_(std::move(path)), trips_(path_.size()), frame_bytes_out_(frame_bytes) {
  stream_ = stub.Interact(&context_);
  stream_->Write(OpenRequest(open));
}

DeviceStream::~DeviceStream() { context_.TryCancel(); }

bool DeviceStream::Attached() {
  pb::Frame frame;
  if (!stream_->Read(&frame)) return false;
  frame_bytes_out_.store(static_cast<int64_t>(frame.ByteSizeLong()));
  return true;
}

pb::InteractRequest DeviceStream::Request(uint64_t sequence) const {
  pb::InteractRequest request;
  pb::ToolPose* pose = request.mutable_pose();
  pose->set_sequence(sequence);
  pose->set_device_time_ns(SteadyNowNs());
  PoseToProto(path_[sequence - 1].X_WD, pose->mutable_pose());
  return request;
}

int64_t DeviceStream::MeanRequestBytes() const {
  // A pose message's size depends on the pose: the mean over the path.
  constexpr uint64_t kSamples = 16;
  const uint64_t count = path_.size();
  if (count == 0) return 0;
  int64_t sampled = 0;
  for (uint64_t k = 0; k < kSamples; ++k) {
    sampled += static_cast<int64_t>(Request(1 + k * (count - 1) / (kSamples - 1)).ByteSizeLong());
  }
  return sampled / static_cast<int64_t>(kSamples);
}

void DeviceStream::Run(const SendSchedule& schedule, bool keep_step_times) {
  std::thread writer([&] {
    SendPaced(
        trips_, schedule, [&](uint64_t sequence) { return stream_->Write(Request(sequence)); },
        [&] { stream_->WritesDone(); });
  });
  Read(schedule, keep_step_times);
  writer.join();
  status_ = stream_->Finish();
}

void DeviceStream::Read(const SendSchedule& schedule, bool keep_step_times) {
  pb::Frame frame;
  uint64_t applied = 0;  // the last pose sequence a frame applied
  while (stream_->Read(&frame)) {
    if (SendSchedule::Clock::now() < schedule.start) continue;
    counts_.Add(frame);
    trips_.MarkAnswered(frame.last_pose_sequence());
    // Only steps that applied a new pose: in the echo's turns the devices
    // are still, and those steps run no stage.
    if (keep_step_times && frame.last_pose_sequence() > applied) {
      step_ms_.push_back(1e-6 * static_cast<double>(frame.timings().step_ns()));
    }
    applied = std::max(applied, frame.last_pose_sequence());
    if (counts_.frames() % 64 == 1) {
      frame_bytes_out_.store(static_cast<int64_t>(frame.ByteSizeLong()));
    }
  }
}

StreamReport DeviceStream::Report(double window_s) {
  StreamReport report;
  counts_.Fill(report, window_s);
  report.sent = static_cast<int64_t>(trips_.sent());
  report.answered = static_cast<int64_t>(trips_.answered());
  report.rtt_ms = Summarize(trips_.rtt_ms());
  return report;
}

grpc::Status DeviceStream::Finish() { return stream_->Finish(); }

}  // namespace hs::cli

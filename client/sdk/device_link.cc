#include "client/sdk/device_link.h"

#include <algorithm>
#include <chrono>

#include "absl/strings/str_cat.h"
#include "client/sdk/grpc_error.h"

namespace hs::sdk {
namespace {

namespace pb = haptics::v1;
using Clock = std::chrono::steady_clock;

Clock::duration Seconds(double s) {
  return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
}

}  // namespace

bool Retried(haptics::Code code) {
  switch (code) {
    case haptics::Code::kAborted:  // taken over
    case haptics::Code::kInvalidArgument:
    case haptics::Code::kPermissionDenied:
    case haptics::Code::kUnauthenticated:
    case haptics::Code::kUnimplemented:
    case haptics::Code::kOk:  // the server ended the stream as asked
      return false;
    default:
      return true;
  }
}

DeviceLink::DeviceLink(std::shared_ptr<grpc::Channel> channel, DeviceConfig config,
                       TripleBuffer<PoseSample>& poses, TripleBuffer<Feed>& feeds)
    : channel_(std::move(channel)),
      config_(std::move(config)),
      poses_(poses),
      feeds_(feeds),
      protocol_(config_) {}

DeviceLink::~DeviceLink() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
    if (stream_ != nullptr) stream_->Cancel();
  }
  changed_.notify_all();
  if (thread_.joinable()) thread_.join();
}

haptics::Error DeviceLink::Start() {
  thread_ = std::thread(&DeviceLink::Run, this);
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return started_; });
  if (start_error_.ok()) return {};
  lock.unlock();
  thread_.join();
  return start_error_;
}

haptics::DeviceState DeviceLink::State() const {
  haptics::DeviceState state;
  state.connected = connected_.load();
  const int64_t rtt = round_trip_ns_.load();
  state.round_trip_s = rtt < 0 ? -1 : static_cast<double>(rtt) * 1e-9;
  const int64_t arrival = model_arrival_ns_.load();
  state.model_age_s = arrival < 0 ? -1 : static_cast<double>(SteadyNowNs() - arrival) * 1e-9;
  state.reconnects = reconnects_.load();
  state.frames = frames_.load();
  state.models = models_.load();
  state.models_rejected = models_rejected_.load();
  std::lock_guard lock(mutex_);
  state.last_error = last_error_;
  state.closed = closed_;
  return state;
}

void DeviceLink::Publish() {
  feeds_.back() = protocol_.feed();
  feeds_.Publish();
}

void DeviceLink::Run() {
  double wait_s = config_.options.reconnect_initial_s;
  for (uint64_t stream = 1;; ++stream) {
    first_frame_ = false;
    const grpc::Status status = RunStream(stream);
    connected_ = false;
    protocol_.End();
    Publish();
    const bool opened = first_frame_.load();
    std::unique_lock lock(mutex_);
    last_error_ = FromGrpc(status);
    if (!started_) {
      // The first stream ended before its first frame: Start reports why.
      started_ = true;
      start_error_ = last_error_;
      if (start_error_.ok()) start_error_ = {haptics::Code::kUnavailable, "the stream ended"};
      changed_.notify_all();
      return;
    }
    if (stopping_ || !Retried(last_error_.code)) {
      closed_ = true;
      return;
    }
    if (opened) wait_s = config_.options.reconnect_initial_s;
    changed_.wait_for(lock, Seconds(wait_s), [&] { return stopping_; });
    if (stopping_) {
      closed_ = true;
      return;
    }
    wait_s = std::min(2 * wait_s, config_.options.reconnect_max_s);
  }
}

grpc::Status DeviceLink::RunStream(uint64_t stream) {
  const pb::InteractRequest::Open open = protocol_.Open();
  protocol_.Begin(stream);
  std::atomic<bool> reading{true};
  std::unique_lock lock(mutex_);
  if (stopping_) return grpc::Status(grpc::StatusCode::CANCELLED, "the device was closed");
  lock.unlock();
  InteractStream::Callbacks callbacks{
      .on_frame = [&](const pb::Frame& frame) { OnFrame(stream, frame); },
      .on_end =
          [&] {
            reading = false;
            changed_.notify_all();
          }};
  std::unique_ptr<InteractPipe> pipe =
      config_.open_pipe ? config_.open_pipe(channel_, open, std::move(callbacks))
                        : std::make_unique<InteractStream>(channel_, open, std::move(callbacks));
  InteractPipe& rw = *pipe;
  lock.lock();
  stream_ = &rw;
  // Stopped between the check and here: the destructor found no stream.
  if (stopping_) rw.Cancel();
  lock.unlock();
  const Clock::time_point opened = Clock::now();
  const Clock::duration period = Seconds(1 / config_.options.rate_hz);
  bool timed_out = false;
  for (Clock::time_point next = opened + period; reading; next += period) {
    if (!first_frame_ && Clock::now() - opened > Seconds(config_.open_timeout_s)) {
      timed_out = true;
      break;
    }
    if (!SendPose(rw)) break;
    // Behind (a slow write): the next pose goes a period from now, not in
    // a burst.
    next = std::max(next, Clock::now());
    lock.lock();
    changed_.wait_until(lock, next, [&] { return stopping_ || !reading; });
    const bool stop = stopping_;
    lock.unlock();
    if (stop) break;
  }
  // A stream the server ended keeps its status for Finish; one this side
  // gives up on is cancelled.
  if (reading) rw.Cancel();
  grpc::Status status = rw.Finish();
  lock.lock();
  stream_ = nullptr;
  lock.unlock();
  if (timed_out) {
    return grpc::Status(grpc::StatusCode::DEADLINE_EXCEEDED,
                        absl::StrCat("no frame from scene '", config_.scene, "' within ",
                                     config_.open_timeout_s, " s"));
  }
  return status;
}

bool DeviceLink::SendPose(InteractPipe& writer) {
  poses_.Take();
  const PoseSample& sample = poses_.front();
  if (sample.time_ns == 0) return true;  // the device has not ticked yet
  pb::InteractRequest request;
  protocol_.PoseRequest(sample, request);
  return writer.Write(request);
}

void DeviceLink::OnFrame(uint64_t stream, const pb::Frame& frame) {
  ++frames_;
  const int64_t now = SteadyNowNs();
  const FrameRead read = protocol_.Read(frame, now);
  if (read.first_frame) {
    first_frame_ = true;
    connected_ = true;
    if (stream > 1) ++reconnects_;
    std::lock_guard lock(mutex_);
    if (!started_) {
      started_ = true;
      changed_.notify_all();
    }
  }
  if (read.round_trip_ns >= 0) round_trip_ns_ = read.round_trip_ns;
  if (read.model_rejected) ++models_rejected_;
  if (read.new_model) {
    ++models_;
    model_arrival_ns_ = now;
  }
  if (read.feed_changed) Publish();
}

}  // namespace hs::sdk

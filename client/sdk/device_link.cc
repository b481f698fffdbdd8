#include "client/sdk/device_link.h"

#include <algorithm>
#include <chrono>

#include "absl/strings/str_cat.h"
#include "client/sdk/grpc_error.h"
#include "common/api/local_model_convert.h"

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

DeviceLink::DeviceLink(std::shared_ptr<grpc::Channel> channel, LinkConfig config,
                       TripleBuffer<PoseSample>& poses, TripleBuffer<Feed>& feeds)
    : channel_(std::move(channel)), config_(std::move(config)), poses_(poses), feeds_(feeds) {}

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
  std::lock_guard lock(mutex_);
  state.last_error = last_error_;
  state.closed = closed_;
  return state;
}

void DeviceLink::Publish() {
  feeds_.back() = feed_;
  feeds_.Publish();
}

void DeviceLink::Run() {
  double wait_s = config_.options.reconnect_initial_s;
  for (uint64_t stream = 1;; ++stream) {
    first_frame_ = false;
    const grpc::Status status = RunStream(stream);
    connected_ = false;
    feed_.connected = false;
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
  pb::InteractRequest::Open open;
  open.set_scene(config_.scene);
  open.set_tool(config_.tool);
  open.set_take_over(config_.options.take_over);
  open.set_frame_rate_hz(config_.options.rate_hz);
  for (pb::Effect effect : {pb::EFFECT_FORCE, pb::EFFECT_FRICTION, pb::EFFECT_LOCAL_MODEL}) {
    open.add_needs(effect);
  }
  std::atomic<bool> reading{true};
  std::unique_lock lock(mutex_);
  if (stopping_) return grpc::Status(grpc::StatusCode::CANCELLED, "the device was closed");
  lock.unlock();
  InteractStream rw(channel_, open,
                    {.on_frame = [&](const pb::Frame& frame) { OnFrame(stream, frame); },
                     .on_end =
                         [&] {
                           reading = false;
                           changed_.notify_all();
                         }});
  lock.lock();
  stream_ = &rw;
  // Stopped between the check and here: the destructor found no stream.
  if (stopping_) rw.Cancel();
  lock.unlock();
  const Clock::time_point opened = Clock::now();
  const Clock::duration period = Seconds(1 / config_.options.rate_hz);
  bool timed_out = false;
  uint64_t sequence = 0;
  for (Clock::time_point next = opened + period; reading; next += period) {
    if (!first_frame_ && Clock::now() - opened > Seconds(config_.open_timeout_s)) {
      timed_out = true;
      break;
    }
    if (!SendPose(rw, sequence)) break;
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

bool DeviceLink::SendPose(InteractStream& writer, uint64_t& sequence) {
  poses_.Take();
  const PoseSample& sample = poses_.front();
  if (sample.time_ns == 0) return true;  // the device has not ticked yet
  pb::InteractRequest request;
  pb::ToolPose* pose = request.mutable_pose();
  pose->set_sequence(++sequence);
  pose->set_device_time_ns(sample.time_ns);
  pose->mutable_pose()->mutable_position_m()->set_x(sample.position_m[0]);
  pose->mutable_pose()->mutable_position_m()->set_y(sample.position_m[1]);
  pose->mutable_pose()->mutable_position_m()->set_z(sample.position_m[2]);
  pb::Quaternion* q = pose->mutable_pose()->mutable_orientation();
  q->set_w(sample.orientation_wxyz[0]);
  q->set_x(sample.orientation_wxyz[1]);
  q->set_y(sample.orientation_wxyz[2]);
  q->set_z(sample.orientation_wxyz[3]);
  const double now_s = static_cast<double>(sample.time_ns) * 1e-9;
  const int64_t round_trip_ns = round_trip_peak_ns_.exchange(-1);
  if (round_trip_ns >= 0) {
    model_requester_.AddRoundTrip(now_s, static_cast<double>(round_trip_ns) * 1e-9);
  }
  const ModelRequest model = model_requester_.ForPose(
      now_s, Vector3d(sample.position_m[0], sample.position_m[1], sample.position_m[2]),
      sample.beyond_validity_ticks);
  pose->set_model_stale(model.model_stale);
  pose->set_validity_radius_m(model.validity_radius_m);
  return writer.Write(request);
}

void DeviceLink::OnFrame(uint64_t stream, const pb::Frame& frame) {
  ++frames_;
  const int64_t now = SteadyNowNs();
  bool changed = false;
  if (!first_frame_) {
    first_frame_ = true;
    connected_ = true;
    feed_.stream = stream;
    feed_.connected = true;
    last_revision_ = 0;
    changed = true;
    if (stream > 1) ++reconnects_;
    std::lock_guard lock(mutex_);
    if (!started_) {
      started_ = true;
      changed_.notify_all();
    }
  }
  if (frame.last_pose_sequence() > 0 && frame.last_pose_device_time_ns() > 0) {
    const int64_t round_trip_ns = now - frame.last_pose_device_time_ns();
    round_trip_ns_ = round_trip_ns;
    int64_t peak = round_trip_peak_ns_.load();
    while (round_trip_ns > peak &&
           !round_trip_peak_ns_.compare_exchange_weak(peak, round_trip_ns)) {
    }
  }
  for (const pb::ToolState& tool : frame.tools()) {
    if (tool.tool() != config_.tool || !tool.has_local_model()) continue;
    const uint64_t revision = tool.local_model().revision();
    if (revision != 0 && revision == last_revision_) continue;
    absl::StatusOr<LocalModel> model = LocalModelFromProto(tool.local_model());
    if (!model.ok()) continue;  // the loop keeps the last model
    last_revision_ = revision;
    feed_.model = *std::move(model);
    feed_.model_stream = stream;
    ++feed_.model_serial;
    ++models_;
    model_arrival_ns_ = now;
    changed = true;
  }
  if (changed) Publish();
}

}  // namespace hs::sdk

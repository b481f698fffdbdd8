#include "client/remote/shaped_stream.h"

namespace hs::cli {

namespace pb = haptics::v1;
using Clock = std::chrono::steady_clock;

SimulatedLink::SimulatedLink(const LinkConditions& conditions)
    : t0_(Clock::now()), up_(conditions, 0), down_(conditions, 1) {}

double SimulatedLink::NowS() const {
  return std::chrono::duration<double>(Clock::now() - t0_).count();
}

sdk::OpenPipe SimulatedLink::Opener() {
  return
      [this](const std::shared_ptr<grpc::Channel>& channel, const pb::InteractRequest::Open& open,
             sdk::InteractStream::Callbacks callbacks) -> std::unique_ptr<sdk::InteractPipe> {
        return std::make_unique<ShapedStream>(*this, channel, open, std::move(callbacks));
      };
}

LinkStats SimulatedLink::Stats() const { return StatsOf(up_, down_); }

ShapedStream::ShapedStream(SimulatedLink& link, const std::shared_ptr<grpc::Channel>& channel,
                           const pb::InteractRequest::Open& open,
                           sdk::InteractStream::Callbacks callbacks)
    : link_(link),
      id_(++link.streams_),
      callbacks_(std::move(callbacks)),
      stream_(channel, open,
              {.on_frame =
                   [this](const pb::Frame& frame) {
                     link_.down_.Push(link_.NowS(), {id_, frame});
                   },
               .on_end = [this] { ended_ = true; }}),
      pump_(&ShapedStream::Pump, this) {}

ShapedStream::~ShapedStream() { StopPump(); }

void ShapedStream::StopPump() {
  stopping_ = true;
  if (pump_.joinable()) pump_.join();
}

void ShapedStream::Pump() {
  const Clock::duration period = std::chrono::milliseconds(1);
  for (Clock::time_point next = Clock::now(); !stopping_; next += period) {
    std::this_thread::sleep_until(next);
    const double now_s = link_.NowS();
    // This thread alone writes to the stream.
    link_.up_.PopDue(now_s, [&](SimulatedLink::Held<pb::InteractRequest> request) {
      if (request.first == id_ && !closed_ && !stream_.Write(request.second)) closed_ = true;
    });
    if (writes_done_.exchange(false)) stream_.WritesDone();
    link_.down_.PopDue(now_s, [&](SimulatedLink::Held<pb::Frame> frame) {
      if (frame.first == id_ && !ended_ && callbacks_.on_frame) callbacks_.on_frame(frame.second);
    });
    if (ended_) break;
  }
  if (callbacks_.on_end) callbacks_.on_end();
}

bool ShapedStream::Write(const pb::InteractRequest& request) {
  if (closed_ || ended_) return false;
  link_.up_.Push(link_.NowS(), {id_, request});
  return true;
}

void ShapedStream::WritesDone() {
  closed_ = true;
  writes_done_ = true;
}

void ShapedStream::Cancel() { stream_.Cancel(); }

grpc::Status ShapedStream::Finish() {
  grpc::Status status = stream_.Finish();
  StopPump();
  return status;
}

}  // namespace hs::cli

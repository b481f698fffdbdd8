#include "client/loadtest/echo_stream.h"

#include <algorithm>
#include <string>
#include <thread>

namespace hs::cli {

namespace pb = haptics::v1;

EchoStream::EchoStream(pb::EchoService::Stub& stub, size_t count, int64_t request_bytes,
                       const std::atomic<int64_t>& frame_bytes)
    : trips_(count), frame_bytes_(frame_bytes) {
  stream_ = stub.Echo(&context_);
  request_.set_reply_bytes(static_cast<uint32_t>(frame_bytes.load()));
  request_.set_sent_ns(SteadyNowNs());
  request_.set_sequence(count);
  // Pad so the message is as large as a device's pose message.
  const int64_t bare = static_cast<int64_t>(request_.ByteSizeLong()) + 2;
  request_.set_payload(std::string(std::max<int64_t>(0, request_bytes - bare), 'p'));
}

bool EchoStream::Write(uint64_t sequence) {
  const int64_t reply_bytes = frame_bytes_.load();
  reply_bytes_ += reply_bytes;
  request_.set_reply_bytes(static_cast<uint32_t>(reply_bytes));
  request_.set_sequence(sequence);
  request_.set_sent_ns(SteadyNowNs());
  return stream_->Write(request_);
}

void EchoStream::Run(const SendSchedule& schedule) {
  std::thread writer([&] {
    SendPaced(
        trips_, schedule, [&](uint64_t sequence) { return Write(sequence); },
        [&] { stream_->WritesDone(); });
  });
  pb::EchoMessage answer;
  while (stream_->Read(&answer)) {
    trips_.MarkAnswered(answer.sequence());
    ++frames_;
  }
  writer.join();
  status_ = stream_->Finish();
}

StreamReport EchoStream::Report(double window_s) {
  StreamReport report;
  report.sent = static_cast<int64_t>(trips_.sent());
  report.answered = static_cast<int64_t>(trips_.answered());
  report.frames = frames_;
  report.frames_per_s = static_cast<double>(frames_) / window_s;
  report.rtt_ms = Summarize(trips_.rtt_ms());
  return report;
}

int64_t EchoStream::mean_reply_bytes() const {
  return trips_.sent() ? reply_bytes_ / static_cast<int64_t>(trips_.sent()) : 0;
}

}  // namespace hs::cli

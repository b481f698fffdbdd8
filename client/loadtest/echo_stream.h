#pragma once
// One stream of the echo baseline of `hapticctl loadtest` (echo_baseline.h)
// with the devices' message sizes: requests as large as a pose message,
// answers as large as the devices' latest frames.

#include <grpcpp/grpcpp.h>

#include <atomic>
#include <memory>

#include "client/loadtest/load_report.h"
#include "client/loadtest/round_trips.h"
#include "client/loadtest/send_schedule.h"
#include "haptics/v1/echo_service.grpc.pb.h"

namespace hs::cli {

class EchoStream {
 public:
  /// Opens an Echo stream for `count` messages of `request_bytes`, each
  /// asking for an answer of `frame_bytes` as it is when sent.
  EchoStream(haptics::v1::EchoService::Stub& stub, size_t count, int64_t request_bytes,
             const std::atomic<int64_t>& frame_bytes);

  /// Sends on `schedule` and reads the answers until the stream ends.
  void Run(const SendSchedule& schedule);

  /// Messages sent and answered, answers as frames, round trips;
  /// frames_per_s over `window_s`.
  StreamReport Report(double window_s);
  const grpc::Status& status() const { return status_; }
  RoundTrips& trips() { return trips_; }
  /// The mean size of the answers asked for.
  int64_t mean_reply_bytes() const;

 private:
  bool Write(uint64_t sequence);

  RoundTrips trips_;
  const std::atomic<int64_t>& frame_bytes_;
  int64_t reply_bytes_ = 0;  // summed over the requests sent
  grpc::ClientContext context_;
  std::unique_ptr<grpc::ClientReaderWriter<haptics::v1::EchoMessage, haptics::v1::EchoMessage>>
      stream_;
  haptics::v1::EchoMessage request_;
  int64_t frames_ = 0;
  grpc::Status status_;
};

}  // namespace hs::cli

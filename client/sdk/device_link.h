#pragma once
// The network side of a Device: a thread of its own that opens the
// Interact stream, sends the device's newest pose at the chosen rate,
// hands each new local model and the stream's state to the device's loop,
// and opens the stream again with exponential back-off when it ends (the
// server gone, the link down), until it is stopped or the server ends it
// for good (the tool taken over, a refused token or request).

#include <grpcpp/grpcpp.h>

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "client/sdk/device_config.h"
#include "client/sdk/device_feed.h"
#include "client/sdk/device_protocol.h"
#include "client/sdk/interact_stream.h"
#include "client/sdk/triple_buffer.h"
#include "haptics/device.h"
#include "haptics/error.h"
#include "haptics/v1/session_service.grpc.pb.h"

namespace hs::sdk {

/// Whether a stream that ended with `code` is opened again.
bool Retried(haptics::Code code);

class DeviceLink {
 public:
  /// Reads poses from `poses` and writes feeds to `feeds` (both outlive it).
  DeviceLink(std::shared_ptr<grpc::Channel> channel, DeviceConfig config,
             TripleBuffer<PoseSample>& poses, TripleBuffer<Feed>& feeds);
  /// Stops the thread: cancels the stream and joins.
  ~DeviceLink();
  DeviceLink(const DeviceLink&) = delete;
  DeviceLink& operator=(const DeviceLink&) = delete;

  /// Starts the thread and waits for the first stream's first frame: OK,
  /// or why the stream ended (then the thread has ended too).
  haptics::Error Start();

  /// The state of the link (DeviceState less the loop's own counts).
  haptics::DeviceState State() const;

 private:
  void Run();
  // One stream, from open to its end; its status.
  grpc::Status RunStream(uint64_t stream);
  // The reader thread of stream `stream`.
  void OnFrame(uint64_t stream, const haptics::v1::Frame& frame);
  // Sends the newest pose on `writer` if there is one; false when the
  // stream is closed.
  bool SendPose(InteractPipe& writer);
  void Publish();

  const std::shared_ptr<grpc::Channel> channel_;
  const DeviceConfig config_;
  TripleBuffer<PoseSample>& poses_;
  TripleBuffer<Feed>& feeds_;
  // The requests and the feed its frames make (protocol_.feed(), which the
  // feeds copy).
  DeviceProtocol protocol_;

  std::thread thread_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  bool stopping_ = false;
  // Start's answer: set when the first stream's first frame came or it ended.
  bool started_ = false;
  haptics::Error start_error_;
  haptics::Error last_error_;
  bool closed_ = false;
  // The running stream, to cancel it on Stop.
  InteractPipe* stream_ = nullptr;

  std::atomic<bool> first_frame_{false};
  std::atomic<bool> connected_{false};
  std::atomic<int64_t> frames_{0};
  std::atomic<int64_t> models_{0};
  std::atomic<int64_t> models_rejected_{0};
  std::atomic<int64_t> reconnects_{0};
  std::atomic<int64_t> round_trip_ns_{-1};
  std::atomic<int64_t> model_arrival_ns_{-1};
};

}  // namespace hs::sdk

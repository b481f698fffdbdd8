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

#include "client/haptic_loop/model_request.h"
#include "client/sdk/device_feed.h"
#include "client/sdk/interact_stream.h"
#include "client/sdk/triple_buffer.h"
#include "haptics/device.h"
#include "haptics/error.h"
#include "haptics/v1/session_service.grpc.pb.h"

namespace hs::sdk {

struct LinkConfig {
  std::string scene;
  std::string tool;
  haptics::DeviceOptions options;
  /// The first frame of a stream comes within this, seconds, or the stream
  /// is given up.
  double open_timeout_s = 5;
};

/// Whether a stream that ended with `code` is opened again.
bool Retried(haptics::Code code);

class DeviceLink {
 public:
  /// Reads poses from `poses` and writes feeds to `feeds` (both outlive it).
  DeviceLink(std::shared_ptr<grpc::Channel> channel, LinkConfig config,
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
  bool SendPose(InteractStream& writer, uint64_t& sequence);
  void Publish();

  const std::shared_ptr<grpc::Channel> channel_;
  const LinkConfig config_;
  TripleBuffer<PoseSample>& poses_;
  TripleBuffer<Feed>& feeds_;
  // The state the feeds copy: the reader thread writes it while a stream
  // runs, the network thread between streams.
  Feed feed_;
  // What each pose asks of the model (network thread only).
  ModelRequester model_requester_;

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
  InteractStream* stream_ = nullptr;

  std::atomic<bool> first_frame_{false};
  std::atomic<bool> connected_{false};
  std::atomic<int64_t> frames_{0};
  std::atomic<int64_t> models_{0};
  std::atomic<int64_t> reconnects_{0};
  std::atomic<int64_t> round_trip_ns_{-1};
  // The longest round trip seen since the last pose went (-1: none).
  std::atomic<int64_t> round_trip_peak_ns_{-1};
  std::atomic<int64_t> model_arrival_ns_{-1};
  uint64_t last_revision_ = 0;
};

}  // namespace hs::sdk

#pragma once
// A simulated link under a device's Interact streams, on the steady clock:
// each pose the device writes and each frame the server sends is held,
// lost or stalled as the link's conditions say (delay_line.h), in order,
// before it goes on. It is how `hapticctl drive --operator --latency-ms
// ...` puts a link between the SDK's Device and the server without
// leaving the process (`hapticctl relay` does the same to real bytes).

#include <grpcpp/grpcpp.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <thread>
#include <utility>

#include "client/remote/delay_line.h"
#include "client/sdk/device_config.h"
#include "client/sdk/interact_stream.h"
#include "haptics/v1/session_service.pb.h"

namespace hs::cli {

/// The two directions of a link, shared by every stream opened over it.
class SimulatedLink {
 public:
  /// `conditions` must pass CheckLinkConditions.
  explicit SimulatedLink(const LinkConditions& conditions);

  /// Opens streams over this link (sdk::DeviceConfig::open_pipe). The link
  /// outlives them.
  sdk::OpenPipe Opener();
  LinkStats Stats() const;

 private:
  friend class ShapedStream;
  // A message and the stream it belongs to: a stream takes only its own
  // (what an earlier connection left on the link is gone with it).
  template <typename T>
  using Held = std::pair<uint64_t, T>;

  double NowS() const;

  const std::chrono::steady_clock::time_point t0_;
  DelayLine<Held<haptics::v1::InteractRequest>> up_;
  DelayLine<Held<haptics::v1::Frame>> down_;
  std::atomic<uint64_t> streams_{0};
};

/// One Interact stream over a SimulatedLink: writes go onto the link's up
/// direction, frames onto its down one, and a thread of its own passes on
/// what is due every millisecond.
class ShapedStream : public sdk::InteractPipe {
 public:
  ShapedStream(SimulatedLink& link, const std::shared_ptr<grpc::Channel>& channel,
               const haptics::v1::InteractRequest::Open& open,
               sdk::InteractStream::Callbacks callbacks);
  /// Stops passing messages on, then cancels and joins the stream.
  ~ShapedStream() override;

  bool Write(const haptics::v1::InteractRequest& request) override;
  /// Says so to the server within a millisecond (what is still on the link
  /// is dropped).
  void WritesDone() override;
  void Cancel() override;
  grpc::Status Finish() override;

 private:
  void Pump();
  void StopPump();

  SimulatedLink& link_;
  const uint64_t id_;
  sdk::InteractStream::Callbacks callbacks_;
  std::atomic<bool> closed_{false};
  std::atomic<bool> writes_done_{false};
  std::atomic<bool> ended_{false};
  std::atomic<bool> stopping_{false};
  // Declared after what its reader's callbacks use.
  sdk::InteractStream stream_;
  std::thread pump_;
};

}  // namespace hs::cli

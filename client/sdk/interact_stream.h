#pragma once
// One SessionService.Interact stream: the Open sent first, a reader thread
// of its own handing each frame to the caller, poses written by the
// caller, and the status the stream ended with. Every device stream of
// the project opens through it: a Device's network thread (device_link.h)
// one per connection, `hapticctl drive` one per path or operator run.

#include <grpcpp/grpcpp.h>

#include <chrono>
#include <functional>
#include <memory>
#include <thread>

#include "haptics/v1/session_service.grpc.pb.h"

namespace hs::sdk {

/// What a device's network thread talks through for one stream: the
/// gRPC stream itself (InteractStream), or one that holds its messages on
/// a simulated link first (client/remote/shaped_stream.h).
class InteractPipe {
 public:
  virtual ~InteractPipe() = default;
  /// Sends a request (a pose); false once the stream is closed.
  virtual bool Write(const haptics::v1::InteractRequest& request) = 0;
  /// Says no more poses come: the server ends the stream (OK).
  virtual void WritesDone() = 0;
  /// Ends the stream from this side (Finish then returns CANCELLED); any
  /// thread may call it.
  virtual void Cancel() = 0;
  /// Waits for the stream's end (after WritesDone, Cancel, the deadline or
  /// the server's end) and returns its status. Once.
  virtual grpc::Status Finish() = 0;
};

class InteractStream : public InteractPipe {
 public:
  /// Called on the reader thread: each frame, then once when the stream
  /// has no more (its end, an error or Cancel).
  struct Callbacks {
    std::function<void(const haptics::v1::Frame&)> on_frame;
    std::function<void()> on_end;
  };

  /// Opens the stream and sends `open`; the reader starts once it is sent.
  /// A deadline of time_point::max() is none.
  InteractStream(const std::shared_ptr<grpc::Channel>& channel,
                 const haptics::v1::InteractRequest::Open& open, Callbacks callbacks,
                 std::chrono::system_clock::time_point deadline =
                     std::chrono::system_clock::time_point::max());
  /// Cancels the stream if it runs and joins the reader.
  ~InteractStream() override;
  InteractStream(const InteractStream&) = delete;
  InteractStream& operator=(const InteractStream&) = delete;

  bool Write(const haptics::v1::InteractRequest& request) override;
  void WritesDone() override;
  void Cancel() override;
  /// Joins the reader (it returns when the stream has ended) and returns
  /// the stream's status.
  grpc::Status Finish() override;

 private:
  grpc::ClientContext context_;
  std::unique_ptr<grpc::ClientReaderWriter<haptics::v1::InteractRequest, haptics::v1::Frame>>
      stream_;
  Callbacks callbacks_;
  std::thread reader_;
  bool finished_ = false;
};

}  // namespace hs::sdk

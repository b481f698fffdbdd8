#pragma once
// The writing half of one stream: the frames a scene offers it, at the rate
// it asked for, through its outbox, serialized and written one at a time to
// its gRPC stream. It calls nothing but its writer and never the runner: a
// frame that cannot be sent ends its own stream (FrameSink's contract).

#include <grpcpp/support/byte_buffer.h>

#include <cstdint>
#include <memory>
#include <mutex>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "common/api/proto_convert.h"
#include "server/frame_message.h"
#include "server/frame_outbox.h"
#include "server/metrics.h"
#include "server/step_snapshot.h"

namespace hs {

/// Frames a viewer may have waiting before the oldest is dropped.
inline constexpr size_t kViewerQueueFrames = 64;
/// The largest frame a stream sends: what a gRPC client takes by default
/// (4 MiB). A larger one ends the stream RESOURCE_EXHAUSTED instead of
/// failing on the client's side.
inline constexpr size_t kMaxFrameBytes = 4 << 20;

/// The frame rate a stream asked for (frame_rate_hz), checked against the
/// scene's: 0 (every step) or 1 to `scene_rate_hz`. INVALID_ARGUMENT naming
/// `field` otherwise, non-finite included.
absl::StatusOr<double> CheckFrameRate(double frame_rate_hz, double scene_rate_hz,
                                      const char* field);

/// Where a FramePump writes: a gRPC stream's reactor.
class FrameWriter {
 public:
  virtual ~FrameWriter() = default;
  /// Starts writing `bytes`, which stay valid until FramePump::WriteDone.
  virtual void StartWrite(const grpc::ByteBuffer* bytes) = 0;
  /// Ends the stream with `status`; called once, with no write in flight.
  virtual void Finish(const absl::Status& status) = 0;
};

class FramePump {
 public:
  struct Options {
    /// The parts of each step the stream receives.
    FrameParts parts;
    /// A device's stream (its own tool's state and local model only), or a
    /// viewer's (every tool's).
    bool device = false;
    /// Frames waiting at most (>= 1, at most kViewerQueueFrames); 1 is
    /// latest-wins. A stream with a frame rate always has 1.
    size_t queue_frames = 1;
    /// Frames a second, 0: every step (CheckFrameRate).
    double frame_rate_hz = 0;
    /// Frames larger than this end the stream RESOURCE_EXHAUSTED.
    size_t max_frame_bytes = kMaxFrameBytes;
  };

  /// `writer` and `metrics` outlive the pump; `stream` is the FrameSink
  /// whose device's tool gets the last applied pose in each frame.
  FramePump(FrameWriter& writer, const FrameSink* stream, Metrics& metrics);

  /// Sets what the stream asked for; before the first Offer.
  void Configure(const Options& options);
  /// A step's frame: queued when due at the stream's rate, written when no
  /// write is in flight.
  void Offer(std::shared_ptr<const StepSnapshot> snapshot);
  /// Sends the frames waiting, then ends the stream with `status`.
  void Close(const absl::Status& status);
  /// Drops the frames waiting and ends the stream with `status` once no
  /// write is in flight.
  void Abort(const absl::Status& status);
  /// The write in flight ended (ok: the frame went out).
  void WriteDone(bool ok);
  /// Close or Abort was called.
  bool closed() const { return outbox_.closed(); }
  /// Runs `start_operation` (a read) unless the stream is closed,
  /// atomically with Finish: no operation starts after Finish.
  template <class F>
  void UnlessClosed(F start_operation) {
    std::lock_guard lock(finish_mu_);
    if (!outbox_.closed()) start_operation();
  }
  /// The scene time from which a frame is due (FrameSink::NextDueS); 0 when
  /// every step's is, and before the first frame. Offer's thread only.
  double next_due_s() const { return options_.frame_rate_hz > 0 ? next_due_s_ : 0; }
  /// Frames dropped because the stream fell behind (not the ones its rate
  /// skips).
  uint64_t dropped() const { return outbox_.dropped(); }

 private:
  // Whether `snapshot` is due at the stream's rate; moves the next due time.
  bool Due(const StepSnapshot& snapshot);
  // Starts the next write or the finish, if any is ready.
  void Pump();

  FrameWriter& writer_;
  const FrameSink* const stream_;
  Metrics& metrics_;
  Options options_;
  // Scene time of the next frame due (Offer's thread only); 0 before the
  // first.
  double next_due_s_ = 0;
  FrameOutbox outbox_;
  std::mutex finish_mu_;     // Finish and the writes it must follow
  ModelsSent models_sent_;   // the writing thread's only
  FrameMessageArena frame_;  // the frame of the write in flight, until serialized
  grpc::ByteBuffer bytes_;   // frame_, serialized: the write in flight
};

}  // namespace hs

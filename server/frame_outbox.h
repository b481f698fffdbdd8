#pragma once
// The frames waiting to be written to one stream, with at most one write in
// flight. Bounded: when full, the oldest waiting frame is dropped and
// counted, so a slow reader never holds up the scene or grows memory. With
// capacity 1 it is latest-wins (device streams).

#include <boost/circular_buffer.hpp>
#include <cstdint>
#include <memory>
#include <mutex>

#include "absl/status/status.h"
#include "server/step_snapshot.h"

namespace hs {

class FrameOutbox {
 public:
  /// What the stream's writer does next.
  struct Next {
    enum Kind { kNothing, kWrite, kFinish } kind = kNothing;
    /// kWrite: the frame, and frames dropped since the stream began.
    std::shared_ptr<const StepSnapshot> snapshot;
    uint64_t dropped = 0;
    /// kFinish: how the stream ends.
    absl::Status status;
  };

  /// Keeps at most `capacity` (>= 1) frames waiting.
  explicit FrameOutbox(size_t capacity);
  /// Keeps at most `capacity` (1 to the constructor's) frames waiting from
  /// now on; before the first Push.
  void Limit(size_t capacity);

  /// Queues a frame (dropping the oldest waiting one when full); ignored
  /// once closed. True when a frame was dropped.
  bool Push(std::shared_ptr<const StepSnapshot> snapshot);
  /// No frames after those waiting; then the stream ends with `status`.
  /// Only the first call counts.
  void Close(const absl::Status& status);
  /// Drops the waiting frames and ends with `status` as soon as no write is
  /// in flight (the client is gone).
  void Abort(const absl::Status& status);

  /// The next action when no write is in flight, else kNothing. kWrite
  /// marks a write in flight until WriteDone; kFinish is returned once.
  Next TakeNext();
  /// The write in flight ended.
  void WriteDone();

  uint64_t dropped() const;
  /// Close or Abort was called.
  bool closed() const;

 private:
  size_t capacity_;
  mutable std::mutex mu_;
  // Fixed storage: no allocation per frame.
  boost::circular_buffer<std::shared_ptr<const StepSnapshot>> waiting_;
  uint64_t dropped_ = 0;
  bool writing_ = false;
  bool closed_ = false;
  bool finished_ = false;
  absl::Status status_;
};

}  // namespace hs

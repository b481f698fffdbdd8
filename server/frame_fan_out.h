#pragma once
// Hands each step's frame to a scene's streams, in step order, on a thread
// of its own (scene-frames): a stream's write can wait on gRPC's locks for
// milliseconds, and a step must not. It is also the one caller of the
// streams: the ends the registry queues (take-overs, silent devices, the
// scene's end) are handed over on the same thread, after the frames of the
// same round. No lock is held while a stream is called: a gate (a flag and
// a count, behind a lock taken only to read or flip them) tells
// WaitForSinkCalls when a call that may name a detached stream is over.
// The thread is woken only for a step some stream takes (FrameSink::
// NextDueS), or when a stream came or an end waits.

#include <atomic>
#include <boost/circular_buffer.hpp>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <thread>
#include <vector>

#include "server/metrics.h"
#include "server/priority_inheriting_mutex.h"
#include "server/step_snapshot.h"
#include "server/stream_registry.h"

namespace hs {

class FrameFanOut {
 public:
  /// Frames stepped and not yet handed over; past this many (the hand-over
  /// stalled for that many steps) the oldest is dropped and counted.
  static constexpr size_t kMaxQueuedFrames = 64;

  /// Starts the thread (SCHED_FIFO at `realtime_priority` when not 0).
  /// `streams` and `metrics` outlive it.
  FrameFanOut(StreamRegistry& streams, Metrics& metrics, int realtime_priority);
  /// Stop() if not stopped yet.
  ~FrameFanOut();
  FrameFanOut(const FrameFanOut&) = delete;
  FrameFanOut& operator=(const FrameFanOut&) = delete;

  /// Queues a step's frame for every stream attached when it is handed over.
  void Push(std::shared_ptr<const StepSnapshot> snapshot);
  /// Hands over every frame queued, then stops the thread. Later calls do
  /// nothing.
  void Stop();
  /// Hands the ends the registry holds to their streams on the calling
  /// thread (for the ends queued after Stop).
  void HandOverEnds();
  /// Returns once no call to a stream that started before it is running:
  /// after a stream left the registry, nothing calls it any more. Aborts
  /// when called from a stream's Offer or Close (it would wait for itself).
  void WaitForSinkCalls();
  /// True on a thread that is inside a stream's Offer or Close.
  static bool InSinkCall();

 private:
  void Run(int realtime_priority);
  // One round of calls to the streams: `snapshot` (may be null) to each
  // attached stream, then the ends queued.
  void CallSinks(const std::shared_ptr<const StepSnapshot>& snapshot);

  StreamRegistry& streams_;
  Metrics& metrics_;
  PriorityInheritingMutex mu_{LockLevel::kFrames};
  std::condition_variable_any cv_;
  // Fixed storage (boost::circular_buffer): no allocation per frame.
  boost::circular_buffer<std::shared_ptr<const StepSnapshot>> queue_{kMaxQueuedFrames};
  bool stop_ = false;

  // The gate: set while a round calls streams, with the rounds begun.
  PriorityInheritingMutex gate_mu_{LockLevel::kFrames};
  std::condition_variable_any gate_cv_;
  bool calling_ = false;
  uint64_t rounds_ = 0;
  std::vector<FrameSink*> offer_to_;  // the calling round's only
  std::vector<SinkEnd> ends_;         // the calling round's only
  // Set by each round that offered a frame: the earliest scene time a
  // stream takes a frame from, and the registry's changes() it saw.
  std::atomic<double> next_due_s_{0};
  std::atomic<uint64_t> changes_seen_{0};

  std::thread thread_;
};

}  // namespace hs

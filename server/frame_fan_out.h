#pragma once
// Hands each step's frame to a scene's streams, in step order, on a thread
// of its own (scene-frames): a stream's write can wait on gRPC's locks for
// milliseconds, and a step must not.

#include <boost/circular_buffer.hpp>
#include <condition_variable>
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
  FrameFanOut(const StreamRegistry& streams, Metrics& metrics, int realtime_priority);
  /// Stop() if not stopped yet.
  ~FrameFanOut();
  FrameFanOut(const FrameFanOut&) = delete;
  FrameFanOut& operator=(const FrameFanOut&) = delete;

  /// Queues a step's frame for every stream attached when it is handed over.
  void Push(std::shared_ptr<const StepSnapshot> snapshot);
  /// Hands over every frame queued, then stops the thread. Later calls do
  /// nothing.
  void Stop();
  /// Returns once no offer that started before the call is running: after
  /// a stream left the registry, no offer to it runs or will run.
  void WaitForOffers();

 private:
  void Run(int realtime_priority);

  const StreamRegistry& streams_;
  Metrics& metrics_;
  PriorityInheritingMutex mu_;
  std::condition_variable_any cv_;
  // Fixed storage (boost::circular_buffer): no allocation per frame.
  boost::circular_buffer<std::shared_ptr<const StepSnapshot>> queue_{kMaxQueuedFrames};
  bool stop_ = false;
  // Held while a frame is offered, so that WaitForOffers (and the
  // registry's lock, which the stepping thread needs) is never held across
  // a stream's write.
  PriorityInheritingMutex offer_mu_;
  std::vector<FrameSink*> offer_to_;  // scene-frames only
  std::thread thread_;
};

}  // namespace hs

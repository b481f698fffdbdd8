#include "server/frame_fan_out.h"

#include <pthread.h>

#include <algorithm>
#include <limits>

#include "common/core/check.h"
#include "server/thread_priority.h"

namespace hs {
namespace {

thread_local bool in_sink_call = false;

}  // namespace

FrameFanOut::FrameFanOut(StreamRegistry& streams, Metrics& metrics, int realtime_priority)
    : streams_(streams), metrics_(metrics) {
  thread_ = std::thread([this, realtime_priority] { Run(realtime_priority); });
}

FrameFanOut::~FrameFanOut() { Stop(); }

bool FrameFanOut::InSinkCall() { return in_sink_call; }

void FrameFanOut::Push(std::shared_ptr<const StepSnapshot> snapshot) {
  // No stream takes this step's frame and none came or waits for its end
  // since the last round: the round would call no stream, so the thread
  // is not woken (at 250 frames a second on a 1 kHz scene, three steps of
  // four).
  if (snapshot->time_s + kFrameDueSlackS < next_due_s_.load(std::memory_order_acquire) &&
      streams_.changes() == changes_seen_.load(std::memory_order_acquire)) {
    return;
  }
  {
    std::lock_guard lock(mu_);
    if (queue_.size() >= kMaxQueuedFrames) {
      queue_.pop_front();
      metrics_.AddFramesDropped(1);
    }
    queue_.push_back(std::move(snapshot));
  }
  cv_.notify_one();
}

void FrameFanOut::Stop() {
  {
    std::lock_guard lock(mu_);
    if (stop_) return;
    stop_ = true;
  }
  cv_.notify_all();
  thread_.join();  // every frame queued is handed over first
}

void FrameFanOut::HandOverEnds() { CallSinks(nullptr); }

void FrameFanOut::WaitForSinkCalls() {
  HS_CHECK(!in_sink_call && "a stream waited for the calls to streams from inside one");
  std::unique_lock lock(gate_mu_);
  const uint64_t round = rounds_;
  gate_cv_.wait(lock, [&] { return !calling_ || rounds_ != round; });
}

void FrameFanOut::CallSinks(const std::shared_ptr<const StepSnapshot>& snapshot) {
  {
    std::unique_lock lock(gate_mu_);
    gate_cv_.wait(lock, [this] { return !calling_; });
    calling_ = true;
    ++rounds_;
  }
  // The gate is up: a stream that leaves the registry from now on waits in
  // WaitForSinkCalls until this round ends, so the streams listed here
  // outlive their calls.
  // Read before the list: a stream that comes after it changes the count.
  const uint64_t changes = streams_.changes();
  if (snapshot) streams_.ListSinks(offer_to_);
  streams_.TakeEnds(ends_);
  in_sink_call = true;
  if (snapshot) {
    double next_due_s = std::numeric_limits<double>::infinity();
    for (FrameSink* sink : offer_to_) {
      sink->Offer(snapshot);
      next_due_s = std::min(next_due_s, sink->NextDueS());
    }
    next_due_s_.store(next_due_s, std::memory_order_release);
    changes_seen_.store(changes, std::memory_order_release);
  }
  for (const SinkEnd& end : ends_) end.sink->Close(end.status);
  in_sink_call = false;
  {
    std::lock_guard lock(gate_mu_);
    calling_ = false;
  }
  gate_cv_.notify_all();
}

void FrameFanOut::Run(int realtime_priority) {
  pthread_setname_np(pthread_self(), "scene-frames");
  // Checked when the server started; should the system refuse now, the
  // frames go out at the default scheduler.
  if (realtime_priority != 0) (void)SetRealtimePriority(realtime_priority);
  std::unique_lock lock(mu_);
  while (true) {
    cv_.wait(lock, [this] { return stop_ || !queue_.empty(); });
    if (queue_.empty()) return;  // stopped, and every frame handed over
    std::shared_ptr<const StepSnapshot> snapshot = std::move(queue_.front());
    queue_.pop_front();
    lock.unlock();
    CallSinks(snapshot);
    lock.lock();
  }
}

}  // namespace hs

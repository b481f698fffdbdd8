#include "server/frame_fan_out.h"

#include <pthread.h>

#include "server/thread_priority.h"

namespace hs {

FrameFanOut::FrameFanOut(const StreamRegistry& streams, Metrics& metrics, int realtime_priority)
    : streams_(streams), metrics_(metrics) {
  thread_ = std::thread([this, realtime_priority] { Run(realtime_priority); });
}

FrameFanOut::~FrameFanOut() { Stop(); }

void FrameFanOut::Push(std::shared_ptr<const StepSnapshot> snapshot) {
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

void FrameFanOut::WaitForOffers() { std::lock_guard offering(offer_mu_); }

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
    {
      std::lock_guard offering(offer_mu_);
      streams_.ListSinks(offer_to_);
      for (FrameSink* sink : offer_to_) sink->Offer(snapshot);
    }
    lock.lock();
  }
}

}  // namespace hs

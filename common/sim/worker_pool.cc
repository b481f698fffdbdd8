#include "common/sim/worker_pool.h"

#include <pthread.h>

namespace hs {

WorkerPool::WorkerPool(int threads, const std::function<void()>& on_start) {
  for (int i = 1; i < threads; ++i) {
    workers_.emplace_back([this, on_start] {
      if (on_start) on_start();
      Work();
    });
  }
}

WorkerPool::~WorkerPool() {
  {
    std::lock_guard lock(mu_);
    stop_ = true;
  }
  wake_.notify_all();
  for (std::thread& worker : workers_) worker.join();
}

void WorkerPool::Drain(absl::FunctionRef<void(int)> task, int n) {
  const auto start = std::chrono::steady_clock::now();
  for (int i = next_.fetch_add(1, std::memory_order_relaxed); i < n;
       i = next_.fetch_add(1, std::memory_order_relaxed)) {
    task(i);
  }
  const auto took = std::chrono::steady_clock::now() - start;
  work_ns_.fetch_add(std::chrono::duration_cast<std::chrono::nanoseconds>(took).count(),
                     std::memory_order_relaxed);
}

void WorkerPool::ForEach(int n, absl::FunctionRef<void(int)> task) {
  if (workers_.empty()) {  // nothing to decide: no clock read
    for (int i = 0; i < n; ++i) task(i);
    return;
  }
  work_ns_.store(0, std::memory_order_relaxed);
  if (n <= 1 || last_work_ < serial_below_) {
    next_.store(0, std::memory_order_relaxed);
    Drain(task, n);
    last_work_ = std::chrono::nanoseconds(work_ns_.load(std::memory_order_relaxed));
    return;
  }
  {
    std::lock_guard lock(mu_);
    task_ = &task;
    n_ = n;
    next_.store(0, std::memory_order_relaxed);
    ++generation_;
  }
  wake_.notify_all();
  Drain(task, n);
  // Every index is taken; wait for the workers still running theirs. A
  // worker that wakes after this returns finds no index left (or a later
  // job, which it reads afresh under the lock).
  std::unique_lock lock(mu_);
  idle_.wait(lock, [this] { return busy_ == 0; });
  task_ = nullptr;
  last_work_ = std::chrono::nanoseconds(work_ns_.load(std::memory_order_relaxed));
}

void WorkerPool::Work() {
  pthread_setname_np(pthread_self(), "step-worker");
  long seen = 0;
  std::unique_lock lock(mu_);
  while (true) {
    wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
    if (stop_) return;
    seen = generation_;
    if (task_ == nullptr) continue;  // the job ended before this worker woke
    const absl::FunctionRef<void(int)> task = *task_;
    const int n = n_;
    ++busy_;
    lock.unlock();
    Drain(task, n);
    lock.lock();
    if (--busy_ == 0) idle_.notify_one();
  }
}

}  // namespace hs

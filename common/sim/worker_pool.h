#pragma once
// A fixed set of worker threads that run the independent parts of one step
// (a scene's tools) beside the stepping thread.
//
// Written here rather than taken from a library: the step needs a blocking
// hand-off with no allocation per call and no spinning. On a 2-core
// machine the stepping thread shares the cores with gRPC, and pools that
// spin between jobs (OpenMP, oneTBB) take that time from the streams.

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

#include "absl/functional/function_ref.h"

namespace hs {

class WorkerPool {
 public:
  /// A pool of `threads` - 1 workers: with the calling thread, `threads`
  /// run at once. 1 or less runs everything on the calling thread. Each
  /// worker first runs `on_start` (when set), e.g. to take the scheduling
  /// of the calling thread.
  explicit WorkerPool(int threads, const std::function<void()>& on_start = {});
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  /// The most tasks that run at once (>= 1).
  int threads() const { return static_cast<int>(workers_.size()) + 1; }

  /// A job runs on the calling thread alone when the last job's work (its
  /// tasks' time summed over the threads) was under `work`: handing a
  /// short job to a worker costs more of a core than it saves (a futex
  /// wake and wait on each side, two context switches), and the job ends
  /// in time anyway. Zero (the default) hands every job of more than one
  /// task to the workers.
  void set_serial_below(std::chrono::nanoseconds work) { serial_below_ = work; }

  /// Runs task(i) for every i in [0, n), on the calling thread and the
  /// workers, and returns when all are done. Which thread runs which i is
  /// not fixed: tasks must not depend on each other or share mutable state.
  /// Not reentrant; one caller at a time.
  void ForEach(int n, absl::FunctionRef<void(int)> task);

 private:
  void Work();
  // Takes indices of the current job until none is left; adds the time it
  // took to work_ns_.
  void Drain(absl::FunctionRef<void(int)> task, int n);

  std::mutex mu_;
  std::condition_variable wake_;                        // a job is posted, or the pool stops
  std::condition_variable idle_;                        // a worker left the job
  long generation_ = 0;                                 // guarded by mu_
  bool stop_ = false;                                   // guarded by mu_
  int busy_ = 0;                                        // workers inside a job; guarded by mu_
  const absl::FunctionRef<void(int)>* task_ = nullptr;  // guarded by mu_
  int n_ = 0;                                           // guarded by mu_
  std::atomic<int> next_{0};                            // the next index to take
  std::atomic<int64_t> work_ns_{0};                     // the current job's work so far
  std::chrono::nanoseconds serial_below_{0};
  std::chrono::nanoseconds last_work_{0};  // the last job's; the caller's only
  std::vector<std::thread> workers_;
};

}  // namespace hs

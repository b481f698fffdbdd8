#pragma once
// A fixed set of worker threads that run the independent parts of one step
// (a scene's tools) beside the stepping thread.
//
// Written here rather than taken from a library: the step needs a blocking
// hand-off with no allocation per call and no spinning. On a 2-core
// machine the stepping thread shares the cores with gRPC, and pools that
// spin between jobs (OpenMP, oneTBB) take that time from the streams.

#include <atomic>
#include <condition_variable>
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

  /// Runs task(i) for every i in [0, n), on the calling thread and the
  /// workers, and returns when all are done. Which thread runs which i is
  /// not fixed: tasks must not depend on each other or share mutable state.
  /// Not reentrant; one caller at a time.
  void ForEach(int n, absl::FunctionRef<void(int)> task);

 private:
  void Work();
  // Takes indices of the current job until none is left.
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
  std::vector<std::thread> workers_;
};

}  // namespace hs

#pragma once
// A mutex whose holder runs at the priority of the threads waiting for it.

#include <pthread.h>

#include "server/lock_order.h"

namespace hs {

/// std::mutex with priority inheritance (POSIX PTHREAD_PRIO_INHERIT): while
/// a thread waits for it, its holder runs at the waiter's priority if that
/// is higher. A real-time stepping thread shares its runner's mutexes with
/// gRPC threads under the default scheduler; with a plain mutex, a gRPC
/// thread preempted while holding one keeps the step waiting behind every
/// other runnable thread (a priority inversion: up to 0.33 ms for the
/// frame queue's lock at 8 devices x 1 kHz). Written by hand because
/// neither the standard library, Abseil nor gRPC has one; it only sets the
/// POSIX attribute. Meets Lockable, for std::lock_guard, std::unique_lock
/// and std::condition_variable_any. A mutex with a LockLevel checks the
/// runtime's lock order (server/lock_order.h) on every lock.
class PriorityInheritingMutex {
 public:
  explicit PriorityInheritingMutex(LockLevel level = LockLevel::kLeaf);
  ~PriorityInheritingMutex();
  PriorityInheritingMutex(const PriorityInheritingMutex&) = delete;
  PriorityInheritingMutex& operator=(const PriorityInheritingMutex&) = delete;

  void lock();
  bool try_lock();
  void unlock();

 private:
  pthread_mutex_t mutex_;
  const LockLevel level_;
};

}  // namespace hs

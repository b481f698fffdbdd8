#include "server/priority_inheriting_mutex.h"

#include <cerrno>

#include "common/core/check.h"

namespace hs {

PriorityInheritingMutex::PriorityInheritingMutex(LockLevel level) : level_(level) {
  pthread_mutexattr_t attributes;
  HS_CHECK(pthread_mutexattr_init(&attributes) == 0);
  HS_CHECK(pthread_mutexattr_setprotocol(&attributes, PTHREAD_PRIO_INHERIT) == 0);
  HS_CHECK(pthread_mutex_init(&mutex_, &attributes) == 0);
  pthread_mutexattr_destroy(&attributes);
}

// Destroying a locked mutex (EBUSY) is a bug in this project.
PriorityInheritingMutex::~PriorityInheritingMutex() {
  HS_CHECK(pthread_mutex_destroy(&mutex_) == 0);
}

// Errors here (EPERM: unlocking a mutex another thread holds; EINVAL) are
// misuse by this project, not conditions to report.
void PriorityInheritingMutex::lock() {
  LockOrderAcquire(level_);
  HS_CHECK(pthread_mutex_lock(&mutex_) == 0);
}

bool PriorityInheritingMutex::try_lock() {
  const int error = pthread_mutex_trylock(&mutex_);
  HS_CHECK(error == 0 || error == EBUSY);
  if (error == 0) LockOrderAcquire(level_);
  return error == 0;
}

void PriorityInheritingMutex::unlock() {
  HS_CHECK(pthread_mutex_unlock(&mutex_) == 0);
  LockOrderRelease(level_);
}

}  // namespace hs

#pragma once
// Tests that build scheduling situations: real-time threads pinned to CPUs.

#include <pthread.h>
#include <sched.h>

#include <vector>

#include "server/thread_priority.h"

namespace hs::testing {

/// Puts the calling thread under SCHED_FIFO at `priority`, then on `cpu`
/// (in that order: under the default scheduler it would wait there behind
/// the real-time threads until their throttling lets it run). False when
/// the system refuses either.
inline bool RunOnCpuAt(int cpu, int priority) {
  cpu_set_t cpus;
  CPU_ZERO(&cpus);
  CPU_SET(cpu, &cpus);
  return SetRealtimePriority(priority).ok() &&
         pthread_setaffinity_np(pthread_self(), sizeof cpus, &cpus) == 0;
}

/// The CPUs this process may run on.
inline std::vector<int> AllowedCpus() {
  cpu_set_t allowed;
  std::vector<int> cpus;
  if (sched_getaffinity(0, sizeof allowed, &allowed) != 0) return cpus;
  for (int cpu = 0; cpu < CPU_SETSIZE; ++cpu) {
    if (CPU_ISSET(cpu, &allowed)) cpus.push_back(cpu);
  }
  return cpus;
}

}  // namespace hs::testing

#pragma once
// Real-time scheduling for the threads that step scenes. On a machine
// shared with other work (the load generator, gRPC's own threads, other
// tenants) a scene's thread at the default scheduler now and then waits a
// millisecond or more to run, and its scene misses steps; under SCHED_FIFO
// it runs as soon as it wakes.

#include "absl/status/status.h"

namespace hs {

/// Puts the calling thread under SCHED_FIFO at `priority` (1..99).
/// INVALID_ARGUMENT outside that range; PERMISSION_DENIED when the system
/// refuses (it needs root, CAP_SYS_NICE or an RLIMIT_RTPRIO that high).
absl::Status SetRealtimePriority(int priority);

/// Whether a thread of this process may take SCHED_FIFO at `priority`:
/// tried on a short-lived thread, so the caller's scheduling is untouched.
/// Errors as SetRealtimePriority.
absl::Status CheckRealtimePriority(int priority);

}  // namespace hs

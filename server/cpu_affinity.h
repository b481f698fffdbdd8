#pragma once
// Which CPUs the server's threads run on (haptic-server --cpus). The
// threads of a device's path wake one another several times a step (gRPC's
// pollers and callback threads, a scene's stepping, worker and frames
// threads); on a virtual machine a wake-up on another CPU costs an
// interprocessor interrupt through the hypervisor, one on the same CPU does
// not. With 16 remote devices on one scene, keeping the server on one CPU
// took its cost a device from 2.5-3.1 % of a core to 1.7-2.0 %
// (docs/scaling.md).

#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"

namespace hs {

/// CPU numbers written as `taskset -c` and /sys/devices/system/cpu/online
/// write them: numbers and ranges, comma-separated ("0", "2-3", "0,4-5");
/// no strides (taskset's "0-8:2").
/// Sorted, each once. INVALID_ARGUMENT when empty, malformed, a range
/// backwards or a number past the kernel's CPU set (CPU_SETSIZE).
absl::StatusOr<std::vector<int>> ParseCpuList(absl::string_view text);

/// The CPUs this process may run on (sched_getaffinity), sorted; empty
/// when the system does not say.
std::vector<int> AllowedCpus();

/// INVALID_ARGUMENT unless `cpus` is non-empty and each is one this
/// process may run on, naming the first that is not.
absl::Status CheckCpusAllowed(const std::vector<int>& cpus);

/// Runs the calling thread, and every thread and process it starts from
/// now on, on `cpus` only. Errors as CheckCpusAllowed, or the system's.
absl::Status RunOnCpus(const std::vector<int>& cpus);

}  // namespace hs

#pragma once
// CPU time of a process on this machine, from /proc (Linux), for the
// server CPU figure of `hapticctl loadtest`.

#include <optional>

namespace hs::cli {

/// User plus system CPU seconds `pid` has used (/proc/PID/stat); nullopt
/// when it cannot be read (no such process, not Linux).
std::optional<double> ProcessCpuSeconds(int pid);

/// User plus system CPU seconds this process has used (getrusage).
double OwnCpuSeconds();

/// The process (of those this user may inspect) holding a TCP socket
/// listening on `port` (/proc/net/tcp and tcp6, then /proc/*/fd);
/// nullopt when none is found.
std::optional<int> FindListeningPid(int port);

/// The 1-minute load average (/proc/loadavg); -1 when unknown.
double LoadAverage1m();

/// CPU seconds the hypervisor has taken from this machine's cores since
/// boot, summed over them ("steal" in /proc/stat); nullopt when unknown.
/// On a virtual machine a burst of it stops every thread, a scene's too.
std::optional<double> MachineStealSeconds();

}  // namespace hs::cli

#include "server/thread_priority.h"

#include <pthread.h>
#include <sched.h>

#include <cstring>
#include <thread>

#include "absl/strings/str_cat.h"

namespace hs {

absl::Status SetRealtimePriority(int priority) {
  if (priority < 1 || priority > 99) {
    return absl::InvalidArgumentError(
        absl::StrCat("real-time priority ", priority, " is outside [1, 99]"));
  }
  sched_param param{};
  param.sched_priority = priority;
  if (const int error = pthread_setschedparam(pthread_self(), SCHED_FIFO, &param); error != 0) {
    return absl::PermissionDeniedError(
        absl::StrCat("SCHED_FIFO at priority ", priority, ": ", std::strerror(error),
                     " (it needs root, CAP_SYS_NICE or an RLIMIT_RTPRIO that high)"));
  }
  return absl::OkStatus();
}

absl::Status CheckRealtimePriority(int priority) {
  absl::Status status;
  std::thread probe([&] { status = SetRealtimePriority(priority); });
  probe.join();
  return status;
}

}  // namespace hs

#pragma once
// CPU seconds of the server and of this process over a load test, split by
// whose turn it was (send_schedule.h): a thread reads both at every slice
// boundary of the devices' schedule (only at its start and at Stop without
// turns).

#include <condition_variable>
#include <functional>
#include <mutex>
#include <optional>
#include <thread>

#include "client/loadtest/send_schedule.h"

namespace hs::cli {

/// Per turn (0: devices, 1: echo): wall, server and client seconds. The
/// server's are unknown (nullopt) when any of its readings in that turn
/// failed.
struct TurnTotals {
  double wall_s[2] = {0, 0};
  std::optional<double> server_s[2] = {0.0, 0.0};
  double client_s[2] = {0, 0};
};

/// Cumulative CPU seconds, read at each boundary on the sampling thread.
struct CpuReaders {
  /// The server's; nullopt when it cannot be read.
  std::function<std::optional<double>()> server;
  /// This process's.
  std::function<double()> client;
};

class TurnCpu {
 public:
  /// Starts sampling: the first readings at `schedule.start`.
  TurnCpu(CpuReaders readers, const SendSchedule& schedule);
  ~TurnCpu();

  /// Takes the last readings now (none when stopped before the start),
  /// stops, and returns the totals. Once.
  TurnTotals Stop();

 private:
  // Waits until `t` or Stop; true when stopped.
  bool StoppedBy(SendSchedule::Clock::time_point t);
  // The end of slice `slice` (0-based); never without turns.
  SendSchedule::Clock::time_point SliceEnd(int slice) const;
  void Sample();

  const CpuReaders readers_;
  const SendSchedule schedule_;
  TurnTotals totals_;  // the sampling thread's until it is joined
  std::mutex mu_;
  std::condition_variable cv_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace hs::cli

#include "client/loadtest/turn_cpu.h"

#include <chrono>
#include <utility>

namespace hs::cli {
namespace {

using Clock = SendSchedule::Clock;

struct Reading {
  Clock::time_point at;
  std::optional<double> server;
  double client;
};

Reading Read(const CpuReaders& readers) {
  return {Clock::now(), readers.server(), readers.client()};
}

}  // namespace

TurnCpu::TurnCpu(CpuReaders readers, const SendSchedule& schedule)
    : readers_(std::move(readers)), schedule_(schedule) {
  thread_ = std::thread([this] { Sample(); });
}

TurnCpu::~TurnCpu() { Stop(); }

TurnTotals TurnCpu::Stop() {
  {
    std::lock_guard lock(mu_);
    stop_ = true;
  }
  cv_.notify_all();
  if (thread_.joinable()) thread_.join();
  return totals_;
}

bool TurnCpu::StoppedBy(Clock::time_point t) {
  std::unique_lock lock(mu_);
  return cv_.wait_until(lock, t, [this] { return stop_; });
}

Clock::time_point TurnCpu::SliceEnd(int slice) const {
  if (schedule_.slice_s <= 0) return Clock::time_point::max();
  return schedule_.start + std::chrono::duration_cast<Clock::duration>(
                               std::chrono::duration<double>((slice + 1) * schedule_.slice_s));
}

void TurnCpu::Sample() {
  if (StoppedBy(schedule_.start)) return;
  Reading last = Read(readers_);
  for (int slice = 0;; ++slice) {
    const bool stopped = StoppedBy(SliceEnd(slice));
    const Reading now = Read(readers_);
    const int turn = slice % 2;
    totals_.wall_s[turn] += std::chrono::duration<double>(now.at - last.at).count();
    totals_.client_s[turn] += now.client - last.client;
    if (totals_.server_s[turn] && now.server && last.server) {
      *totals_.server_s[turn] += *now.server - *last.server;
    } else {
      totals_.server_s[turn].reset();
    }
    last = now;
    if (stopped) return;
  }
}

}  // namespace hs::cli

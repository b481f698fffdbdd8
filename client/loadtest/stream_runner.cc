#include "client/loadtest/stream_runner.h"

#include <atomic>
#include <chrono>
#include <sstream>
#include <thread>

namespace hs::cli {

std::string ProgressLine(std::string_view phase, double elapsed_s, double duration_s,
                         const std::vector<const RoundTrips*>& trips) {
  uint64_t sent = 0, answered = 0;
  for (const RoundTrips* t : trips) {
    sent += t->sent();
    answered += t->answered();
  }
  std::ostringstream line;
  line << "loadtest: " << phase << " " << static_cast<int>(elapsed_s) << "/" << duration_s << " s, "
       << trips.size() << " streams, " << sent << " sent, " << answered << " answered";
  return line.str();
}

void RunStreams(const std::vector<std::function<void()>>& runs,
                const std::vector<const RoundTrips*>& trips, std::string_view phase,
                double duration_s, std::ostream* progress) {
  using Clock = std::chrono::steady_clock;
  std::vector<std::thread> threads;
  std::atomic<size_t> done{0};
  for (const std::function<void()>& run : runs) {
    threads.emplace_back([&] {
      run();
      ++done;
    });
  }
  const Clock::time_point begin = Clock::now();
  Clock::time_point last_line = begin;
  while (done.load() < runs.size()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    if (progress == nullptr || Clock::now() - last_line < std::chrono::seconds(1)) continue;
    last_line = Clock::now();
    *progress << ProgressLine(phase, std::chrono::duration<double>(last_line - begin).count(),
                              duration_s, trips)
              << std::endl;
  }
  for (std::thread& t : threads) t.join();
}

}  // namespace hs::cli

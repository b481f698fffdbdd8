#include "client/loadtest/stream_runner.h"

#include <gtest/gtest.h>

#include <atomic>
#include <sstream>

namespace hs::cli {
namespace {

// Every run runs, each once, and all have returned when RunStreams does.
TEST(StreamRunnerTest, RunsEveryStream) {
  std::atomic<int> ran{0};
  std::vector<std::function<void()>> runs(5, [&] { ++ran; });
  std::ostringstream progress;
  RunStreams(runs, {}, "devices", 1, &progress);
  EXPECT_EQ(ran.load(), 5);
  RunStreams({}, {}, "none", 1, nullptr);
}

// The progress line sums the streams' messages and counts whole seconds.
TEST(StreamRunnerTest, ProgressLine) {
  RoundTrips a(3), b(3);
  a.MarkSent(1);
  a.MarkSent(2);
  a.MarkAnswered(1);
  b.MarkSent(1);
  EXPECT_EQ(ProgressLine("devices", 2.9, 10, {&a, &b}),
            "loadtest: devices 2/10 s, 2 streams, 3 sent, 1 answered");
}

}  // namespace
}  // namespace hs::cli

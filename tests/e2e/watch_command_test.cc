#include "client/watch_command.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "client/exit_codes.h"
#include "tests/server/test_server.h"

namespace hs::cli {
namespace {

class WatchCommandTest : public ::testing::Test {
 protected:
  WatchCommandTest() {
    server_.Create(hs::testing::SmallScene("s"));
    args_.server.address = server_.address();
    args_.scene = "s";
  }
  int Lines() const {
    const std::string text = out_.str();
    return static_cast<int>(std::count(text.begin(), text.end(), '\n'));
  }

  hs::testing::TestServer server_;
  WatchArgs args_;
  std::ostringstream out_, err_;
};

// --frames N prints N frames, one line each, and exits 0; --json lines parse
// as frames with consecutive steps.
TEST_F(WatchCommandTest, FramesAsLinesAndJson) {
  args_.max_frames = 5;
  ASSERT_EQ(RunWatch(args_, out_, err_), kExitOk) << err_.str();
  EXPECT_EQ(Lines(), 5);
  out_.str("");
  args_.json = true;
  args_.parts = {"poses"};
  ASSERT_EQ(RunWatch(args_, out_, err_), kExitOk) << err_.str();
  std::istringstream lines(out_.str());
  std::string line;
  int64_t previous = -1;
  while (std::getline(lines, line)) {
    const int64_t step = std::stoll(nlohmann::json::parse(line)["step"].get<std::string>());
    if (previous >= 0) {
      EXPECT_EQ(step, previous + 1);
    }
    previous = step;
  }
}

// --summary --duration prints per-second lines whose frame counts are near
// the scene's 1 kHz rate, and exits 0 at the end of the duration.
TEST_F(WatchCommandTest, SummaryPerSecond) {
  args_.summary = true;
  args_.json = true;
  args_.duration_s = 1.5;
  ASSERT_EQ(RunWatch(args_, out_, err_), kExitOk) << err_.str();
  std::istringstream lines(out_.str());
  std::string line;
  ASSERT_TRUE(std::getline(lines, line));
  const nlohmann::json first = nlohmann::json::parse(line);
  // Loose bounds: a loaded 2-core machine may run late, never 2x fast.
  EXPECT_GT(first["frames"].get<int>(), 300);
  EXPECT_LE(first["frames"].get<int>(), 1100);
  EXPECT_EQ(first["last_step"].get<int64_t>() - first["first_step"].get<int64_t>() + 1,
            first["frames"].get<int64_t>() + first["dropped_frames"].get<int64_t>());
}

// An unknown scene exits NOT_FOUND; a scene deleted under the viewer ends
// the stream UNAVAILABLE.
TEST_F(WatchCommandTest, UnknownAndDeletedScene) {
  args_.scene = "nope";
  EXPECT_EQ(RunWatch(args_, out_, err_), kExitNotFound);
  args_.scene = "s";
  args_.summary = true;
  std::thread deleter([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    server_.server().registry().Delete("s").IgnoreError();
  });
  EXPECT_EQ(RunWatch(args_, out_, err_), kExitUnavailable);
  deleter.join();
  EXPECT_NE(err_.str().find("UNAVAILABLE: "), std::string::npos) << err_.str();
}

}  // namespace
}  // namespace hs::cli

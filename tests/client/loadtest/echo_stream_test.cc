#include "client/loadtest/echo_stream.h"

#include <gtest/gtest.h>

#include "client/loadtest/echo_baseline.h"

namespace hs::cli {
namespace {

// Against the in-process echo server every message is answered once, each
// answer counted as a frame, and the replies asked for are as large as the
// devices' latest frame.
TEST(EchoStreamTest, EveryMessageAnswered) {
  absl::StatusOr<std::unique_ptr<EchoBaselineServer>> server = EchoBaselineServer::Start();
  ASSERT_TRUE(server.ok()) << server.status();
  auto stub = haptics::v1::EchoService::NewStub(
      grpc::CreateChannel((*server)->address(), grpc::InsecureChannelCredentials()));
  const std::atomic<int64_t> frame_bytes{300};
  EchoStream echo(*stub, 30, 80, frame_bytes);
  echo.Run({.start = SendSchedule::Clock::now(), .rate_hz = 1000});
  ASSERT_TRUE(echo.status().ok()) << echo.status().error_message();
  const StreamReport report = echo.Report(2.0);
  EXPECT_EQ(report.sent, 30);
  EXPECT_EQ(report.answered, 30);
  EXPECT_EQ(report.frames, 30);
  EXPECT_EQ(report.rtt_ms.count, 30);
  EXPECT_DOUBLE_EQ(report.frames_per_s, 15);
  EXPECT_EQ(echo.mean_reply_bytes(), 300);
}

}  // namespace
}  // namespace hs::cli

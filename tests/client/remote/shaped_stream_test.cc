#include "client/remote/shaped_stream.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <vector>

#include "tests/server/test_server.h"

namespace hs::cli {
namespace {

namespace pb = haptics::v1;
using Clock = std::chrono::steady_clock;

pb::InteractRequest::Open OpenOf(const std::string& tool) {
  pb::InteractRequest::Open open;
  open.set_scene("s");
  open.set_tool(tool);
  return open;
}

pb::InteractRequest PoseRequest(uint64_t sequence) {
  pb::InteractRequest request;
  request.mutable_pose()->set_sequence(sequence);
  *request.mutable_pose()->mutable_pose() = hs::testing::PoseAt(0, 0, 0.05);
  return request;
}

class ShapedStreamTest : public ::testing::Test {
 protected:
  ShapedStreamTest() { server_.Create(hs::testing::SmallScene("s")); }

  // Opens a stream over `link` recording, for each pose applied, when its
  // frame came.
  std::unique_ptr<sdk::InteractPipe> Open(SimulatedLink& link, const std::string& tool = "probe") {
    return link.Opener()(server_.channel(), OpenOf(tool),
                         {.on_frame =
                              [this](const pb::Frame& frame) {
                                std::lock_guard lock(mutex_);
                                ++frames_;
                                if (frame.last_pose_sequence() > applied_) {
                                  applied_ = frame.last_pose_sequence();
                                  applied_at_.push_back(Clock::now());
                                }
                              },
                          .on_end = [this] { ++ends_; }});
  }
  uint64_t applied() {
    std::lock_guard lock(mutex_);
    return applied_;
  }

  hs::testing::TestServer server_;
  std::mutex mutex_;
  int frames_ = 0;
  uint64_t applied_ = 0;
  std::vector<Clock::time_point> applied_at_;
  std::atomic<int> ends_{0};
};

TEST_F(ShapedStreamTest, EachPoseIsAppliedNoSoonerThanTheRoundTrip) {
  // 80 ms round trip: the frame applying a pose comes at least 80 ms after
  // it was written (40 ms up, 40 ms down), in order; the link says it
  // held each message 40 ms each way and lost none.
  SimulatedLink link({.latency_ms = 80, .seed = 3});
  std::unique_ptr<sdk::InteractPipe> stream = Open(link);
  std::vector<Clock::time_point> written;
  for (uint64_t sequence = 1; sequence <= 5; ++sequence) {
    written.push_back(Clock::now());
    ASSERT_TRUE(stream->Write(PoseRequest(sequence)));
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  const Clock::time_point deadline = Clock::now() + std::chrono::seconds(10);
  while (applied() < 5 && Clock::now() < deadline) std::this_thread::yield();
  ASSERT_EQ(applied(), 5u);
  {
    std::lock_guard lock(mutex_);
    ASSERT_EQ(applied_at_.size(), 5u);
    for (size_t i = 0; i < applied_at_.size(); ++i) {
      EXPECT_GE(applied_at_[i] - written[i], std::chrono::milliseconds(80)) << "pose " << i + 1;
    }
  }
  stream->Cancel();
  EXPECT_EQ(stream->Finish().error_code(), grpc::StatusCode::CANCELLED);
  EXPECT_EQ(ends_, 1);
  const LinkStats stats = link.Stats();
  EXPECT_NEAR(stats.uplink_mean_ms, 40, 1e-9);
  EXPECT_NEAR(stats.downlink_mean_ms, 40, 1e-9);
  EXPECT_EQ(stats.poses_lost + stats.frames_lost + stats.poses_stalled + stats.frames_stalled, 0);
}

TEST_F(ShapedStreamTest, ALostLinkLosesEveryPoseAndTheServersEndStillComes) {
  // Every message lost: no pose is applied and no frame comes, the
  // server's refusal of an unknown tool still ends the stream with its
  // status, once, and a write after the end is refused.
  SimulatedLink link({.loss = 1, .seed = 3});
  std::unique_ptr<sdk::InteractPipe> stream = Open(link);
  for (uint64_t sequence = 1; sequence <= 3; ++sequence)
    ASSERT_TRUE(stream->Write(PoseRequest(sequence)));
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  EXPECT_EQ(applied(), 0u);
  EXPECT_EQ(link.Stats().poses_lost, 3);
  stream->Cancel();
  stream->Finish();

  std::unique_ptr<sdk::InteractPipe> refused = Open(link, "nope");
  EXPECT_EQ(refused->Finish().error_code(), grpc::StatusCode::NOT_FOUND);
  EXPECT_FALSE(refused->Write(PoseRequest(1)));
  EXPECT_EQ(ends_, 2);
  std::lock_guard lock(mutex_);
  EXPECT_EQ(frames_, 0);
}

}  // namespace
}  // namespace hs::cli

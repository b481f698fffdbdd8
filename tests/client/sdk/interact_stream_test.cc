#include "client/sdk/interact_stream.h"

#include <gtest/gtest.h>

#include <atomic>

#include "tests/server/test_server.h"

namespace hs::sdk {
namespace {

namespace pb = haptics::v1;

pb::InteractRequest::Open OpenOf(const std::string& tool) {
  pb::InteractRequest::Open open;
  open.set_scene("s");
  open.set_tool(tool);
  return open;
}

pb::InteractRequest PoseRequest(uint64_t sequence, double z) {
  pb::InteractRequest request;
  request.mutable_pose()->set_sequence(sequence);
  *request.mutable_pose()->mutable_pose() = hs::testing::PoseAt(0, 0, z);
  return request;
}

class InteractStreamTest : public ::testing::Test {
 protected:
  InteractStreamTest() { server_.Create(hs::testing::SmallScene("s")); }

  hs::testing::TestServer server_;
  std::atomic<uint64_t> applied_{0};
  std::atomic<int> frames_{0};
  std::atomic<int> ends_{0};
  InteractStream::Callbacks callbacks_{.on_frame =
                                           [this](const pb::Frame& frame) {
                                             ++frames_;
                                             applied_ = frame.last_pose_sequence();
                                           },
                                       .on_end = [this] { ++ends_; }};
};

TEST_F(InteractStreamTest, PosesAppliedAndEndedOk) {
  // Poses written reach the server (its frames report the last one applied),
  // and WritesDone ends the stream OK with one on_end after the frames.
  InteractStream stream(server_.channel(), OpenOf("probe"), callbacks_);
  for (uint64_t sequence = 1; sequence <= 3; ++sequence) {
    ASSERT_TRUE(stream.Write(PoseRequest(sequence, 0.05)));
  }
  while (applied_ < 3) std::this_thread::yield();
  stream.WritesDone();
  EXPECT_TRUE(stream.Finish().ok());
  EXPECT_GT(frames_, 0);
  EXPECT_EQ(ends_, 1);
}

TEST_F(InteractStreamTest, RefusalKeepsTheServersStatus) {
  // An unknown tool ends the stream with the server's NOT_FOUND and no frame.
  InteractStream stream(server_.channel(), OpenOf("nope"), callbacks_);
  const grpc::Status status = stream.Finish();
  EXPECT_EQ(status.error_code(), grpc::StatusCode::NOT_FOUND) << status.error_message();
  EXPECT_EQ(frames_, 0);
  EXPECT_EQ(ends_, 1);
}

TEST_F(InteractStreamTest, CancelAndDestructorEndTheStream) {
  // Cancel ends a running stream CANCELLED; a stream dropped unfinished is
  // cancelled and its reader joined by the destructor.
  {
    InteractStream stream(server_.channel(), OpenOf("probe"), callbacks_);
    while (frames_ == 0) std::this_thread::yield();
    stream.Cancel();
    EXPECT_EQ(stream.Finish().error_code(), grpc::StatusCode::CANCELLED);
  }
  EXPECT_EQ(ends_, 1);
  { InteractStream stream(server_.channel(), OpenOf("probe"), callbacks_); }
  EXPECT_EQ(ends_, 2);
}

}  // namespace
}  // namespace hs::sdk

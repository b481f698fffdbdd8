// The echo baseline server: each message answered in order with its
// sequence and send time and the payload size asked (capped at 1 MiB),
// streams independent of each other, and open streams cancelled when it
// goes.

#include "client/loadtest/echo_baseline.h"

#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>

#include <chrono>

#include "haptics/v1/echo_service.grpc.pb.h"

namespace hs::cli {
namespace {

namespace pb = haptics::v1;

using EchoStream = grpc::ClientReaderWriter<pb::EchoMessage, pb::EchoMessage>;

struct Client {
  explicit Client(const std::string& address)
      : stub(pb::EchoService::NewStub(
            grpc::CreateChannel(address, grpc::InsecureChannelCredentials()))) {
    context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(30));
    stream = stub->Echo(&context);
  }
  // Sends one message and reads its answer (false when either fails).
  bool RoundTrip(uint64_t sequence, int64_t sent_ns, uint32_t reply_bytes, pb::EchoMessage& got) {
    pb::EchoMessage m;
    m.set_sequence(sequence);
    m.set_sent_ns(sent_ns);
    m.set_reply_bytes(reply_bytes);
    m.set_payload(std::string(100, 'x'));
    return stream->Write(m) && stream->Read(&got);
  }

  std::unique_ptr<pb::EchoService::Stub> stub;
  grpc::ClientContext context;
  std::unique_ptr<EchoStream> stream;
};

// Answers carry the message's sequence and send time and a payload of
// reply_bytes 'e's (not the request's payload), at most 1 MiB; closing the
// stream ends it OK.
TEST(EchoBaselineTest, AnswersEachMessage) {
  const absl::StatusOr<std::unique_ptr<EchoBaselineServer>> server = EchoBaselineServer::Start();
  ASSERT_TRUE(server.ok()) << server.status();
  EXPECT_EQ((*server)->address().rfind("127.0.0.1:", 0), 0u) << (*server)->address();
  Client client((*server)->address());
  const uint32_t sizes[] = {0, 1, 64, 1000, 1 << 20, (1 << 20) + 1, 3 << 20};
  for (uint64_t i = 0; i < std::size(sizes); ++i) {
    pb::EchoMessage got;
    ASSERT_TRUE(client.RoundTrip(i + 1, 1000 * static_cast<int64_t>(i) - 5, sizes[i], got)) << i;
    EXPECT_EQ(got.sequence(), i + 1);
    EXPECT_EQ(got.sent_ns(), 1000 * static_cast<int64_t>(i) - 5);
    EXPECT_EQ(got.payload(), std::string(std::min<uint32_t>(sizes[i], 1 << 20), 'e')) << i;
    EXPECT_EQ(got.reply_bytes(), 0u);
  }
  ASSERT_TRUE(client.stream->WritesDone());
  pb::EchoMessage none;
  EXPECT_FALSE(client.stream->Read(&none));
  EXPECT_TRUE(client.stream->Finish().ok());
}

// Streams open side by side are each answered with their own messages.
TEST(EchoBaselineTest, StreamsAreIndependent) {
  const auto server = EchoBaselineServer::Start();
  ASSERT_TRUE(server.ok()) << server.status();
  Client a((*server)->address()), b((*server)->address());
  for (uint64_t i = 0; i < 20; ++i) {
    pb::EchoMessage from_a, from_b;
    ASSERT_TRUE(a.RoundTrip(i, 1, 8, from_a));
    ASSERT_TRUE(b.RoundTrip(1000 + i, 2, 16, from_b));
    EXPECT_EQ(from_a.sequence(), i);
    EXPECT_EQ(from_b.sequence(), 1000 + i);
    EXPECT_EQ(from_a.payload().size(), 8u);
    EXPECT_EQ(from_b.payload().size(), 16u);
  }
}

// Two servers listen on ports of their own; a server going away ends the
// streams still open on it with an error.
TEST(EchoBaselineTest, OwnPortAndOpenStreamsEndWithIt) {
  auto first = EchoBaselineServer::Start();
  auto second = EchoBaselineServer::Start();
  ASSERT_TRUE(first.ok() && second.ok());
  EXPECT_NE((*first)->address(), (*second)->address());
  Client client((*first)->address());
  pb::EchoMessage got;
  ASSERT_TRUE(client.RoundTrip(1, 0, 4, got));
  first->reset();
  EXPECT_FALSE(client.stream->Read(&got));
  EXPECT_FALSE(client.stream->Finish().ok());
}

}  // namespace
}  // namespace hs::cli

#include "server/raw_message.h"

#include <gtest/gtest.h>

#include <string>

#include "google/protobuf/util/message_differencer.h"
#include "haptics/v1/scene.pb.h"

namespace hs {
namespace {

namespace pb = haptics::v1;

// A message serialized into a byte buffer parses back equal, and a buffer
// written twice holds only the second message.
TEST(RawMessageTest, RoundTrip) {
  pb::SceneSpec spec;
  spec.set_name("round trip");
  spec.set_step_s(0.001);
  spec.add_objects()->set_name(std::string(100000, 'x'));  // several slices' worth
  grpc::ByteBuffer bytes;
  pb::SceneSpec other;
  other.set_name("first");
  ASSERT_TRUE(SerializeMessage(other, bytes).ok());
  ASSERT_TRUE(SerializeMessage(spec, bytes).ok());
  pb::SceneSpec back;
  ASSERT_TRUE(ParseMessage(bytes, back).ok());
  EXPECT_TRUE(google::protobuf::util::MessageDifferencer::Equals(back, spec));
  // Parsing leaves the buffer as it was: it parses again.
  pb::SceneSpec again;
  ASSERT_TRUE(ParseMessage(bytes, again).ok());
  EXPECT_EQ(again.name(), "round trip");
}

// Bytes that are not the message are INVALID_ARGUMENT naming its type.
TEST(RawMessageTest, GarbageIsInvalidArgument) {
  const std::string garbage = "\xff\xff\xff\xff\x0f not a message";
  grpc::Slice slice(garbage);
  grpc::ByteBuffer bytes(&slice, 1);
  pb::SceneSpec spec;
  const absl::Status status = ParseMessage(bytes, spec);
  EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(status.message().find("haptics.v1.SceneSpec"), std::string::npos) << status;
}

// A message with no field set (zero bytes) parses over what the target
// held: every field unset.
TEST(RawMessageTest, EmptyMessageParsesOver) {
  grpc::ByteBuffer bytes;
  ASSERT_TRUE(SerializeMessage(pb::SceneSpec(), bytes).ok());
  pb::SceneSpec spec;
  spec.set_name("stale");
  ASSERT_TRUE(ParseMessage(bytes, spec).ok());
  EXPECT_EQ(spec.name(), "");
}

}  // namespace
}  // namespace hs

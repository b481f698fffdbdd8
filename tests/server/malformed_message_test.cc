// Bytes that are no message of the method's request type get
// INVALID_ARGUMENT from every method, streams included, and change nothing.

#include <grpcpp/generic/generic_stub.h>
#include <gtest/gtest.h>

#include <future>

#include "tests/server/test_server.h"

namespace hs::testing {
namespace {

// Not a protobuf message: a field tag with wire type 7, which does not exist.
const std::string kGarbage = "\x0f\xff\xff\xff garbage";

grpc::Status CallUnary(TestServer& server, const std::string& method) {
  grpc::GenericStub stub(server.channel());
  auto context = ContextWithin(5);
  grpc::Slice slice(kGarbage);
  grpc::ByteBuffer request(&slice, 1), response;
  std::promise<grpc::Status> done;
  stub.UnaryCall(context.get(), method, grpc::StubOptions(), &request, &response,
                 [&](grpc::Status s) { done.set_value(s); });
  return done.get_future().get();
}

// Opens a stream on `method`, sends the garbage, half-closes, reads to the
// end; the status and how many messages came back.
std::pair<grpc::Status, int> CallStream(TestServer& server, const std::string& method) {
  grpc::GenericStub stub(server.channel());
  grpc::CompletionQueue queue;
  auto context = ContextWithin(5);
  auto call = stub.PrepareCall(context.get(), method, &queue);
  void* tag;
  bool ok;
  call->StartCall(reinterpret_cast<void*>(1));
  queue.Next(&tag, &ok);
  grpc::Slice slice(kGarbage);
  grpc::ByteBuffer request(&slice, 1);
  call->Write(request, reinterpret_cast<void*>(2));
  queue.Next(&tag, &ok);
  call->WritesDone(reinterpret_cast<void*>(3));
  queue.Next(&tag, &ok);
  int messages = 0;
  grpc::ByteBuffer response;
  while (true) {
    call->Read(&response, reinterpret_cast<void*>(4));
    queue.Next(&tag, &ok);
    if (!ok) break;
    ++messages;
  }
  grpc::Status status;
  call->Finish(&status, reinterpret_cast<void*>(5));
  queue.Next(&tag, &ok);
  return {status, messages};
}

TEST(MalformedMessageTest, EverySceneServiceMethodSaysInvalidArgument) {
  TestServer server;
  server.Create(SmallScene("s"));
  const int64_t revision = server.Get("s").revision();
  for (const char* method : {"CreateScene", "GetScene", "GetGeometry", "ListScenes", "DeleteScene",
                             "AddObject", "UpdateObject", "RemoveObject", "SetEffects"}) {
    const grpc::Status status =
        CallUnary(server, std::string("/haptics.v1.SceneService/") + method);
    EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT)
        << method << ": " << status.error_message();
  }
  const auto [status, messages] = CallStream(server, "/haptics.v1.SceneService/UploadModel");
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << status.error_message();
  EXPECT_EQ(messages, 0);
  EXPECT_EQ(server.Get("s").revision(), revision);
}

// Both stream kinds end with INVALID_ARGUMENT, no frame sent, when their
// first message is no request.
TEST(MalformedMessageTest, EverySessionServiceMethodSaysInvalidArgument) {
  TestServer server;
  server.Create(SmallScene("s"));
  for (const char* method :
       {"/haptics.v1.SessionService/Interact", "/haptics.v1.SessionService/Watch"}) {
    const auto [status, messages] = CallStream(server, method);
    EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT)
        << method << ": " << status.error_message();
    EXPECT_EQ(messages, 0) << method;
  }
  EXPECT_EQ(server.Get("s").devices(), 0);
}

}  // namespace
}  // namespace hs::testing

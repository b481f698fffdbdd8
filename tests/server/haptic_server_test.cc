#include "server/haptic_server.h"

#include <grpcpp/generic/generic_stub.h>
#include <gtest/gtest.h>

#include <future>

#include "tests/server/test_server.h"

namespace hs::testing {
namespace {

// grpc.health.v1.Health/Check for the whole server; the response's bytes.
std::string HealthCheck(TestServer& server, grpc::Status& status) {
  grpc::GenericStub stub(server.channel());
  auto context = ContextWithin(10);
  grpc::Slice empty("");  // HealthCheckRequest{service: ""} is empty
  grpc::ByteBuffer request(&empty, 1);
  grpc::ByteBuffer response;
  std::promise<grpc::Status> done;
  stub.UnaryCall(context.get(), "/grpc.health.v1.Health/Check", grpc::StubOptions(), &request,
                 &response, [&](grpc::Status s) { done.set_value(s); });
  status = done.get_future().get();
  std::vector<grpc::Slice> slices;
  std::string bytes;
  if (status.ok() && response.Dump(&slices).ok()) {
    for (const grpc::Slice& s : slices)
      bytes.append(reinterpret_cast<const char*>(s.begin()), s.size());
  }
  return bytes;
}

// The server answers grpc.health.v1 checks with SERVING while it runs and
// NOT_SERVING once it drains for shutdown; draining ends streams with
// UNAVAILABLE.
TEST(HapticServerTest, HealthServingThenNotServing) {
  TestServer server;
  server.Create(SmallScene("h"));
  grpc::Status status;
  EXPECT_EQ(HealthCheck(server, status), std::string("\x08\x01", 2));  // SERVING
  ASSERT_TRUE(status.ok()) << status.error_message();

  pb::WatchRequest watch;
  watch.set_scene("h");
  auto context = ContextWithin(10);
  auto viewer = server.sessions().Watch(context.get(), watch);
  pb::Frame frame;
  ASSERT_TRUE(viewer->Read(&frame));
  server.server().Drain();
  EXPECT_EQ(HealthCheck(server, status), std::string("\x08\x02", 2));  // NOT_SERVING
  while (viewer->Read(&frame)) {
  }
  EXPECT_EQ(viewer->Finish().error_code(), grpc::StatusCode::UNAVAILABLE);
}

// Server reflection lists the haptics.v1 services
// (grpc.reflection.v1alpha, list_services).
TEST(HapticServerTest, ReflectionListsServices) {
  TestServer server;
  grpc::GenericStub stub(server.channel());
  auto context = ContextWithin(10);
  grpc::CompletionQueue cq;
  auto call = stub.PrepareCall(
      context.get(), "/grpc.reflection.v1alpha.ServerReflection/ServerReflectionInfo", &cq);
  void* tag = nullptr;
  bool ok = false;
  auto await = [&](intptr_t expected) {
    EXPECT_TRUE(cq.Next(&tag, &ok));
    EXPECT_EQ(reinterpret_cast<intptr_t>(tag), expected);
    return ok;
  };
  call->StartCall(reinterpret_cast<void*>(1));
  ASSERT_TRUE(await(1));
  // ServerReflectionRequest{list_services: "*"}: field 7, length 1.
  grpc::Slice request_bytes(std::string("\x3a\x01*", 3));
  grpc::ByteBuffer request(&request_bytes, 1);
  call->Write(request, reinterpret_cast<void*>(2));
  ASSERT_TRUE(await(2));
  grpc::ByteBuffer response;
  call->Read(&response, reinterpret_cast<void*>(3));
  ASSERT_TRUE(await(3));
  std::vector<grpc::Slice> slices;
  ASSERT_TRUE(response.Dump(&slices).ok());
  std::string bytes;
  for (const grpc::Slice& s : slices) {
    bytes.append(reinterpret_cast<const char*>(s.begin()), s.size());
  }
  EXPECT_NE(bytes.find("haptics.v1.SceneService"), std::string::npos);
  EXPECT_NE(bytes.find("haptics.v1.SessionService"), std::string::npos);
  EXPECT_NE(bytes.find("grpc.health.v1.Health"), std::string::npos);
  context->TryCancel();
  grpc::Status status;
  call->Finish(&status, reinterpret_cast<void*>(4));
  await(4);
}

// Streams past max_clients are refused with RESOURCE_EXHAUSTED; one frees
// its place when it ends.
TEST(HapticServerTest, ClientLimit) {
  ServerLimits limits;
  limits.max_clients = 1;
  TestServer server(limits);
  server.Create(SmallScene("one"));
  pb::WatchRequest watch;
  watch.set_scene("one");
  auto first_context = ContextWithin(10);
  auto first = server.sessions().Watch(first_context.get(), watch);
  pb::Frame frame;
  ASSERT_TRUE(first->Read(&frame));
  auto second_context = ContextWithin(10);
  auto second = server.sessions().Watch(second_context.get(), watch);
  while (second->Read(&frame)) {
  }
  EXPECT_EQ(second->Finish().error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  first_context->TryCancel();
  while (first->Read(&frame)) {
  }
  first->Finish();
  EXPECT_NE(server.metrics().Text().find("hs_frames_sent_total"), std::string::npos);
}

// An address other machines reach is refused without TLS unless
// insecure_listen says so; the check runs before anything binds (192.0.2.1
// is a documentation address no interface here holds).
TEST(HapticServerTest, RemoteListenNeedsTlsOrInsecureListen) {
  Metrics metrics;
  ServerOptions options;
  for (const char* listen : {"0.0.0.0:0", "[::]:0", "192.0.2.1:0"}) {
    options.listen = listen;
    absl::StatusOr<std::unique_ptr<HapticServer>> server = HapticServer::Start(options, metrics);
    ASSERT_FALSE(server.ok()) << listen;
    EXPECT_EQ(server.status().code(), absl::StatusCode::kFailedPrecondition) << listen;
    EXPECT_NE(server.status().message().find("--insecure-listen"), std::string::npos);
  }
  options.insecure_listen = true;
  absl::StatusOr<std::unique_ptr<HapticServer>> server = HapticServer::Start(options, metrics);
  ASSERT_FALSE(server.ok());
  EXPECT_EQ(server.status().code(), absl::StatusCode::kUnavailable) << server.status();
}

}  // namespace
}  // namespace hs::testing

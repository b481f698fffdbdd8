// The built haptic-server on Agones: with AGONES_SDK_HTTP_PORT set it tells
// a stand-in SDK endpoint it is Ready with its scene's label, that it is
// Allocated when a device joins and asks to be shut down once it has left;
// with the SDK failing it serves its clients as usual and says so in its
// log; without the variable it sends nothing.

#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <thread>

#include "haptics/v1/scene_service.grpc.pb.h"
#include "haptics/v1/session_service.grpc.pb.h"
#include "tests/server/agones/fake_agones_sdk.h"
#include "tests/server/server_process.h"
#include "tests/server/test_server.h"

namespace hs {
namespace {

namespace pb = haptics::v1;
using testing::FakeAgonesSdk;
using testing::ServerProcess;

const std::vector<std::string> kFastAgones = {"--agones-health-interval-s", "0.1",
                                              "--agones-idle-shutdown-s", "0.3"};

std::vector<std::string> SdkAt(const FakeAgonesSdk& fake) {
  return {"AGONES_SDK_HTTP_PORT=" + std::to_string(fake.port())};
}

// A device takes the demo scene's probe, reads `frames` frames and leaves.
void DeviceVisits(int port, int frames) {
  auto stub = pb::SessionService::NewStub(
      grpc::CreateChannel("127.0.0.1:" + std::to_string(port), grpc::InsecureChannelCredentials()));
  const std::unique_ptr<grpc::ClientContext> context = testing::ContextWithin(20);
  auto stream = testing::OpenDevice(*stub, *context, "probe on torus", "probe");
  ASSERT_NE(stream, nullptr);
  pb::Frame frame;
  for (int i = 0; i < frames; ++i) ASSERT_TRUE(stream->Read(&frame));
  stream->WritesDone();
  while (stream->Read(&frame)) {
  }
  EXPECT_TRUE(stream->Finish().ok());
}

TEST(AgonesServerTest, ReadyLabelledAllocatedThenShutDownWhenIdle) {
  FakeAgonesSdk fake;
  ServerProcess server(kFastAgones, SdkAt(fake));
  ASSERT_GT(server.port(), 0) << server.startup();
  ASSERT_TRUE(fake.WaitFor("POST", "/ready"));
  ASSERT_TRUE(fake.WaitFor("PUT", "/metadata/label"));
  ASSERT_TRUE(fake.WaitFor("POST", "/health", 2));
  EXPECT_EQ(fake.Count("POST", "/allocate"), 0);
  for (const FakeAgonesSdk::Request& r : fake.requests()) {
    if (r.target == "/metadata/label") {
      EXPECT_EQ(r.body, R"({"key":"scene","value":"probe-on-torus"})");
    }
  }
  // A scene created over the API, first by name, does not relabel it.
  auto scenes = pb::SceneService::NewStub(grpc::CreateChannel(
      "127.0.0.1:" + std::to_string(server.port()), grpc::InsecureChannelCredentials()));
  pb::CreateSceneRequest create;
  *create.mutable_spec() = testing::SmallScene("a scene first by name");
  pb::SceneInfo info;
  ASSERT_TRUE(scenes->CreateScene(testing::ContextWithin(10).get(), create, &info).ok());
  ASSERT_TRUE(fake.WaitFor("POST", "/health", fake.Count("POST", "/health") + 3));
  EXPECT_EQ(fake.Count("PUT", "/metadata/label"), 1);
  DeviceVisits(server.port(), 50);
  EXPECT_TRUE(fake.WaitFor("POST", "/allocate"));
  ASSERT_TRUE(fake.WaitFor("POST", "/shutdown"));
  // Agones answers a shutdown with SIGTERM: the server drains and exits 0.
  EXPECT_EQ(server.StopWith(SIGTERM), 0);
}

TEST(AgonesServerTest, ServesItsClientsWhenTheSdkIsDown) {
  FakeAgonesSdk fake;
  fake.SetFailing(true);
  ServerProcess server(kFastAgones, SdkAt(fake));
  ASSERT_GT(server.port(), 0) << server.startup();
  EXPECT_NE(server.LineWith("clients are served as usual"), "");
  DeviceVisits(server.port(), 200);
  EXPECT_GE(fake.Count("POST", "/ready"), 1);
  EXPECT_EQ(fake.Count("POST", "/allocate"), 0);  // nothing past Ready while it fails
  EXPECT_EQ(server.StopWith(SIGTERM), 0);
}

TEST(AgonesServerTest, WithoutTheVariableNothingIsSent) {
  FakeAgonesSdk fake;
  ServerProcess server(kFastAgones);
  ASSERT_GT(server.port(), 0) << server.startup();
  DeviceVisits(server.port(), 50);
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  EXPECT_TRUE(fake.requests().empty());
}

}  // namespace
}  // namespace hs

// The C++ SDK's Device through libhaptics_client, against the built
// haptic-server with the demo scene (probe_on_torus: the probe, a 2 cm
// cube, above the organ, a torus of 400 N/m whose top is at z = 0.08 m
// under the probe).
#include "haptics/client.h"

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <memory>
#include <string>
#include <thread>

#include "tests/common/scratch_dir.h"
#include "tests/server/server_process.h"

namespace {

using haptics::Device;
using haptics::Pose;
using haptics::Session;
using haptics::TickOutput;

constexpr char kScene[] = "probe on torus";
constexpr double kOrganStiffness = 400;
// Where the probe's bottom face rests on the organ: the torus's top.
constexpr double kOrganTop = 0.08;
constexpr double kHalfProbe = 0.01;
// Pressed 5 mm into the organ.
constexpr double kPressedZ = kOrganTop + kHalfProbe - 0.005;

Pose At(double z) {
  Pose pose;
  pose.position_m[0] = 0.1;
  pose.position_m[2] = z;
  return pose;
}

// A 127.0.0.1 port that was free a moment ago (bound, then closed).
int FreePort() {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t size = sizeof address;
  EXPECT_EQ(bind(fd, reinterpret_cast<sockaddr*>(&address), size), 0);
  EXPECT_EQ(getsockname(fd, reinterpret_cast<sockaddr*>(&address), &size), 0);
  close(fd);
  return ntohs(address.sin_port);
}

std::string Address(int port) { return "127.0.0.1:" + std::to_string(port); }

std::unique_ptr<Session> Connect(int port) {
  haptics::SessionOptions options;
  options.connect_timeout_s = 5;
  auto session = Session::Connect(Address(port), options);
  EXPECT_TRUE(session.ok()) << session.error().ToString();
  return session.ok() ? *std::move(session) : nullptr;
}

// Ticks at about 1 kHz at `pose` until `done` holds of the output, at most
// `max_ticks` times; the last output.
TickOutput TickUntil(Device& device, const Pose& pose,
                     const std::function<bool(const TickOutput&)>& done, int max_ticks = 10000) {
  TickOutput out;
  for (int k = 0; k < max_ticks; ++k) {
    out = device.Tick(pose);
    if (done(out)) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return out;
}

bool Touching(const TickOutput& out) {
  return (out.flags & haptics::kConnected) && (out.flags & haptics::kTouching) &&
         out.force_n[2] > 1;
}

// Moves the device from the probe's home (z = 0.1) down to kPressedZ in
// 100 ticks, then holds it until it touches and its force has settled: 50
// ticks in a row within 1 mN of the one before. A model that arrives late
// (a loaded machine) changes the force by at most 0.25 N a tick (the
// loop's switch step), so the first touching tick may be on the way.
TickOutput Press(Device& device) {
  for (int k = 0; k <= 100; ++k) {
    device.Tick(At(0.1 + (kPressedZ - 0.1) * k / 100.0));
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  double last_force_n = 0;
  int steady_ticks = 0;
  return TickUntil(device, At(kPressedZ), [&](const TickOutput& out) {
    const bool steady = Touching(out) && std::abs(out.force_n[2] - last_force_n) < 1e-3;
    last_force_n = out.force_n[2];
    steady_ticks = steady ? steady_ticks + 1 : 0;
    return steady_ticks >= 50;
  });
}

// A session on the server at `port` and a device on the probe, pressed
// into the organ; the device is null (the test failed) when it cannot open.
struct Pressing {
  std::unique_ptr<Session> session;
  std::unique_ptr<Device> device;
  TickOutput out;
};

Pressing PressOn(int port) {
  Pressing p;
  p.session = Connect(port);
  if (p.session == nullptr) return p;
  auto device = p.session->OpenDevice(kScene, "probe");
  EXPECT_TRUE(device.ok()) << device.error().ToString();
  if (!device.ok()) return p;
  p.device = *std::move(device);
  p.out = Press(*p.device);
  return p;
}

TEST(DeviceTest, FeelsTheOrganItPresses) {
  // A device pressed 5 mm into the organ feels its spring: 400 N/m x 5 mm
  // up, within the mesh's faceting (the top face lies up to 0.8 mm under
  // the torus's top).
  hs::testing::ServerProcess server;
  ASSERT_GT(server.port(), 0) << server.startup();
  const Pressing pressing = PressOn(server.port());
  ASSERT_NE(pressing.device, nullptr);
  const TickOutput& out = pressing.out;
  EXPECT_TRUE(out.ok());
  EXPECT_NEAR(out.force_n[2], kOrganStiffness * 0.005, kOrganStiffness * 0.0008);
  EXPECT_NEAR(out.force_n[0], 0, 0.05);
  EXPECT_NEAR(out.force_n[1], 0, 0.05);
  const haptics::DeviceState state = pressing.device->State();
  EXPECT_TRUE(state.connected);
  EXPECT_GT(state.models, 0);
  EXPECT_GT(state.round_trip_s, 0);
  EXPECT_GE(state.model_age_s, 0);
  EXPECT_EQ(state.reconnects, 0);
}

TEST(DeviceTest, BadPoseIsRefusedAndHoldsTheLastForce) {
  // A non-finite position or a quaternion that is not unit returns
  // kInvalidPose with the force of the tick before, unchanged.
  hs::testing::ServerProcess server;
  ASSERT_GT(server.port(), 0) << server.startup();
  const Pressing pressing = PressOn(server.port());
  ASSERT_NE(pressing.device, nullptr);
  const TickOutput& pressed = pressing.out;
  ASSERT_TRUE(Touching(pressed));
  Device& device = *pressing.device;
  Pose nan = At(kPressedZ);
  nan.position_m[1] = std::nan("");
  Pose stretched = At(kPressedZ);
  stretched.orientation_wxyz[0] = 1.01;
  Pose infinite = At(kPressedZ);
  infinite.orientation_wxyz[3] = INFINITY;
  for (const Pose& bad : {nan, stretched, infinite}) {
    const TickOutput out = device.Tick(bad);
    EXPECT_EQ(out.status, haptics::TickStatus::kInvalidPose);
    for (int i = 0; i < 3; ++i) EXPECT_EQ(out.force_n[i], pressed.force_n[i]);
  }
  EXPECT_EQ(device.State().rejected_poses, 3);
}

TEST(DeviceTest, OpenNamesWhatIsWrong) {
  // Open fails, naming the cause, on an unknown scene or tool, a refused
  // token and a server that is not there.
  const std::filesystem::path tokens = hs::ScratchDir("sdk_tokens") / "tokens";
  std::ofstream(tokens) << "sha256:" << std::string(64, '0') << " admin *\n";
  hs::testing::ServerProcess server({"--tokens", tokens.string()});
  ASSERT_GT(server.port(), 0) << server.startup();
  haptics::SessionOptions with_token;
  with_token.token = "not-a-token-the-server-knows";
  auto session = Session::Connect(Address(server.port()), with_token);
  ASSERT_TRUE(session.ok()) << session.error().ToString();
  auto refused = (*session)->OpenDevice(kScene, "probe");
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().code, haptics::Code::kUnauthenticated);
  EXPECT_EQ(refused.error().ToString().rfind("UNAUTHENTICATED: ", 0), 0u);

  hs::testing::ServerProcess open_server;
  auto open_session = Connect(open_server.port());
  ASSERT_NE(open_session, nullptr);
  auto no_scene = open_session->OpenDevice("no such scene", "probe");
  ASSERT_FALSE(no_scene.ok());
  EXPECT_EQ(no_scene.error().code, haptics::Code::kNotFound);
  EXPECT_NE(no_scene.error().ToString().find("no such scene"), std::string::npos);
  auto no_tool = open_session->OpenDevice(kScene, "scalpel");
  ASSERT_FALSE(no_tool.ok());
  EXPECT_EQ(no_tool.error().code, haptics::Code::kNotFound);
  EXPECT_NE(no_tool.error().message.find("scalpel"), std::string::npos);

  // A port nothing listens on: one the kernel gave and took back.
  const int port = FreePort();
  haptics::SessionOptions quick;
  quick.connect_timeout_s = 0.5;
  auto nobody = Session::Connect(Address(port), quick);
  ASSERT_FALSE(nobody.ok());
  EXPECT_EQ(nobody.error().code, haptics::Code::kUnavailable);
  EXPECT_NE(nobody.error().message.find(Address(port)), std::string::npos);
}

TEST(DeviceTest, TickGoesOnWhileTheServerIsStoppedAndFeelsNothingOnceItIsGone) {
  // With the server frozen (SIGSTOP) the device keeps rendering its last
  // model; once the server is gone the link says so and the force is zero.
  hs::testing::ServerProcess server;
  ASSERT_GT(server.port(), 0) << server.startup();
  const Pressing pressing = PressOn(server.port());
  ASSERT_NE(pressing.device, nullptr);
  ASSERT_TRUE(Touching(pressing.out));
  Device& device = *pressing.device;
  server.Signal(SIGSTOP);
  // 500 ticks while no frame can come: each returns the local model's force.
  for (int k = 0; k < 500; ++k) {
    const TickOutput out = device.Tick(At(kPressedZ));
    ASSERT_TRUE(Touching(out)) << "tick " << k;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  server.StopWith(SIGKILL);
  const TickOutput gone =
      TickUntil(device, At(kPressedZ), [](const TickOutput& out) { return out.flags == 0; });
  EXPECT_EQ(gone.flags, 0u);
  for (double f : gone.force_n) EXPECT_EQ(f, 0);
  EXPECT_FALSE(device.State().connected);
  EXPECT_NE(device.State().last_error.code, haptics::Code::kOk);
}

TEST(DeviceTest, ReconnectsWhenTheServerComesBack) {
  // A server restarted on the same port: the device opens its stream again
  // by itself, is seated anew, and feels the organ again.
  auto server = std::make_unique<hs::testing::ServerProcess>();
  ASSERT_GT(server->port(), 0) << server->startup();
  const int port = server->port();
  const Pressing pressing = PressOn(port);
  ASSERT_NE(pressing.device, nullptr);
  ASSERT_TRUE(Touching(pressing.out));
  Device& device = *pressing.device;
  server->StopWith(SIGKILL);
  server.reset();
  TickUntil(device, At(kPressedZ), [](const TickOutput& out) { return out.flags == 0; });
  server = std::make_unique<hs::testing::ServerProcess>(std::vector<std::string>{},
                                                        std::vector<std::string>{}, Address(port));
  ASSERT_EQ(server->port(), port) << server->startup();
  // The device goes home meanwhile, is seated there on the new stream and
  // presses again.
  TickUntil(device, At(0.1), [](const TickOutput& out) { return out.flags & haptics::kHasModel; });
  const TickOutput again = Press(device);
  EXPECT_TRUE(Touching(again));
  EXPECT_NEAR(again.force_n[2], kOrganStiffness * 0.005, kOrganStiffness * 0.0008);
  EXPECT_EQ(device.State().reconnects, 1);
  EXPECT_TRUE(device.State().connected);
}

}  // namespace

// The C++ SDK's Watcher through libhaptics_client, against the built
// haptic-server with the demo scene and a Device pressing on the organ.
#include "haptics/client.h"

#include <gtest/gtest.h>

#include <atomic>
#include <thread>

#include "tests/server/server_process.h"

namespace {

using haptics::Frame;
using haptics::Session;

// The probe's home (0.1, 0, 0.1), pressed 5 mm into the organ (its top at
// z = 0.08 under the probe's 2 cm cube).
haptics::Pose Pressed() {
  haptics::Pose pose;
  pose.position_m[0] = 0.1;
  pose.position_m[2] = 0.085;
  return pose;
}

const haptics::ToolFrame* Probe(const Frame& frame) {
  for (const haptics::ToolFrame& tool : frame.tools) {
    if (tool.tool == "probe") return &tool;
  }
  return nullptr;
}

TEST(WatcherTest, SeesTheContactsOfAPressingDevice) {
  // A viewer asking for contacts and forces sees the probe touch the organ
  // and the force the server computes there, in its callback and in
  // Latest; poses were not asked for and stay zero.
  hs::testing::ServerProcess server;
  ASSERT_GT(server.port(), 0) << server.startup();
  auto session = Session::Connect("127.0.0.1:" + std::to_string(server.port()));
  ASSERT_TRUE(session.ok()) << session.error().ToString();
  std::atomic<int> touching_frames{0};
  haptics::WatchOptions options;
  options.poses = false;
  options.on_frame = [&](const Frame& frame) {
    const haptics::ToolFrame* probe = Probe(frame);
    if (probe != nullptr && !probe->contacts.empty() && probe->contacts[0].object == "organ") {
      ++touching_frames;
    }
  };
  auto watcher = (*session)->Watch("probe on torus", options);
  ASSERT_TRUE(watcher.ok()) << watcher.error().ToString();
  auto device = (*session)->OpenDevice("probe on torus", "probe");
  ASSERT_TRUE(device.ok()) << device.error().ToString();
  for (int k = 0; k < 10000 && touching_frames == 0; ++k) {
    (*device)->Tick(Pressed());
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  EXPECT_GT(touching_frames, 0);
  Frame latest;
  ASSERT_TRUE((*watcher)->Latest(&latest));
  const haptics::ToolFrame* probe = Probe(latest);
  ASSERT_NE(probe, nullptr);
  EXPECT_GT(probe->force_n[2], 0);
  EXPECT_EQ(probe->device_pose.position_m[2], 0);
  EXPECT_FALSE(probe->has_local_model);
  EXPECT_GT(latest.step, 0);
  (*watcher)->Close();
  for (int k = 0; k < 10000 && !(*watcher)->ended(); ++k) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  EXPECT_TRUE((*watcher)->ended());
  EXPECT_TRUE((*watcher)->status().ok()) << (*watcher)->status().ToString();
}

TEST(WatcherTest, UnknownSceneIsNotFound) {
  // Watching a scene the server does not have fails with NOT_FOUND naming it.
  hs::testing::ServerProcess server;
  ASSERT_GT(server.port(), 0) << server.startup();
  auto session = Session::Connect("127.0.0.1:" + std::to_string(server.port()));
  ASSERT_TRUE(session.ok()) << session.error().ToString();
  auto watcher = (*session)->Watch("nowhere");
  ASSERT_FALSE(watcher.ok());
  EXPECT_EQ(watcher.error().code, haptics::Code::kNotFound);
  EXPECT_NE(watcher.error().message.find("nowhere"), std::string::npos);
}

}  // namespace

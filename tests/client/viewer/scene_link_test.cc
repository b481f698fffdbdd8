// The bridge's link to one scene: it comes to know the scene (tools,
// revision, geometry) and its frames, fetches the geometry again when the
// revision moves, and says in words when the scene is not there.

#include "client/viewer/scene_link.h"

#include <gtest/gtest.h>

#include <chrono>
#include <functional>
#include <thread>

#include "nlohmann/json.hpp"
#include "tests/server/test_server.h"

namespace hs::cli {
namespace {

namespace pb = haptics::v1;

// Waits (at most 20 s, so that a broken link fails rather than hangs) until
// `done` holds; the test then checks what it found.
bool WaitUntil(const std::function<bool()>& done) {
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (!done()) {
    if (std::chrono::steady_clock::now() > give_up) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return true;
}

std::vector<std::string> ObjectNames(const std::string& geometry_json) {
  std::vector<std::string> names;
  // Named: a range-for over a member of a temporary would outlive it.
  const nlohmann::json geometry = nlohmann::json::parse(geometry_json);
  for (const auto& object : geometry.at("objects")) {
    names.push_back(object["name"]);
  }
  return names;
}

// The link's state is the server's scene: its tools, its revision, its
// objects in the geometry; and frames of it arrive, counted from 1.
TEST(SceneLinkTest, KnowsTheSceneAndItsFrames) {
  hs::testing::TestServer server;
  server.Create(hs::testing::SmallScene("linked"));
  SceneLink link(server.channel(), "linked");
  ASSERT_TRUE(WaitUntil([&] { return link.state().connected && link.latest().frame; }))
      << link.state().message;
  const SceneLink::State s = link.state();
  EXPECT_EQ(s.scene, "linked");
  EXPECT_EQ(s.message, "");
  EXPECT_EQ(s.tools, std::vector<std::string>{"probe"});
  EXPECT_EQ(s.revision, server.Get("linked").revision());
  EXPECT_DOUBLE_EQ(s.step_s, 0.001);
  ASSERT_NE(s.geometry_json, nullptr);
  EXPECT_EQ(ObjectNames(*s.geometry_json), (std::vector<std::string>{"table", "probe"}));
  const SceneLink::Latest latest = link.latest();
  EXPECT_GE(latest.count, 1u);
  ASSERT_EQ(latest.frame->tools_size(), 1);
  EXPECT_EQ(latest.frame->tools(0).tool(), "probe");
}

// An object added to the scene moves its revision: the link lists the new
// tool and fetches the geometry that has it.
TEST(SceneLinkTest, NewRevisionBringsNewGeometry) {
  hs::testing::TestServer server;
  server.Create(hs::testing::SmallScene("linked"));
  SceneLink link(server.channel(), "linked");
  ASSERT_TRUE(WaitUntil([&] { return link.state().geometry_json != nullptr; }));
  const int64_t before = link.state().revision;
  pb::AddObjectRequest add;
  add.set_scene("linked");
  *add.mutable_object() = hs::testing::SmallScene("x", /*second_tool=*/true).objects(2);
  pb::SceneInfo info;
  ASSERT_TRUE(server.scenes().AddObject(hs::testing::ContextWithin(10).get(), add, &info).ok());
  ASSERT_TRUE(WaitUntil([&] { return link.state().revision == info.revision(); }));
  const SceneLink::State s = link.state();
  EXPECT_GT(s.revision, before);
  EXPECT_EQ(s.tools, (std::vector<std::string>{"probe", "stylus"}));
  EXPECT_EQ(ObjectNames(*s.geometry_json), (std::vector<std::string>{"table", "probe", "stylus"}));
}

// A scene the server lacks: not connected, and the message names it.
TEST(SceneLinkTest, UnknownSceneIsSaidInWords) {
  hs::testing::TestServer server;
  SceneLink link(server.channel(), "nowhere");
  ASSERT_TRUE(WaitUntil([&] { return link.state().message != "connecting"; }));
  const SceneLink::State s = link.state();
  EXPECT_FALSE(s.connected);
  EXPECT_EQ(s.message, "no scene 'nowhere' on the server");
  EXPECT_EQ(s.geometry_json, nullptr);
  EXPECT_EQ(link.latest().frame, nullptr);
}

}  // namespace
}  // namespace hs::cli

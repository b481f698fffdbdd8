// What the Agones lifecycle reads of a server: its scene's name and the
// streams over all its scenes, from a registry of in-process scenes.

#include "server/agones/server_activity.h"

#include <gtest/gtest.h>

#include <memory>

#include "server/scene_registry.h"
#include "tests/common/scratch_dir.h"
#include "tests/server/test_server.h"

namespace hs {
namespace {

// A stream that takes frames and drops them.
class NullSink : public FrameSink {
 public:
  void Offer(std::shared_ptr<const StepSnapshot>) override {}
  void Close(const absl::Status&) override {}
};

class ServerActivityTest : public ::testing::Test {
 protected:
  Metrics metrics_;
  SceneRegistry registry_{ServerLimits{}, ScratchDir("server_activity_models").string(), metrics_};
};

// With no scene the server's own name stands, possibly "", and nothing is
// attached.
TEST_F(ServerActivityTest, NoScenes) {
  const ServerActivity named = ActivityOf(registry_, "demo");
  EXPECT_EQ(named.scene, "demo");
  EXPECT_EQ(named.devices, 0);
  EXPECT_EQ(ActivityOf(registry_, "").scene, "");
}

// The scene named stays; without one the first scene by name is the
// server's.
TEST_F(ServerActivityTest, SceneIsTheGivenOneOrTheFirstByName) {
  ASSERT_TRUE(registry_.Create(testing::SmallScene("b"), "").ok());
  ASSERT_TRUE(registry_.Create(testing::SmallScene("a"), "").ok());
  EXPECT_EQ(ActivityOf(registry_, "b").scene, "b");
  EXPECT_EQ(ActivityOf(registry_, "").scene, "a");
}

// Devices and viewers add up over all scenes, those attached now and those
// that ever joined; a detached one still counts as joined.
TEST_F(ServerActivityTest, StreamsAddUpOverScenes) {
  ASSERT_TRUE(registry_.Create(testing::SmallScene("a", /*second_tool=*/true), "").ok());
  ASSERT_TRUE(registry_.Create(testing::SmallScene("b"), "").ok());
  const std::shared_ptr<SceneRunner> a = *registry_.Find("a");
  const std::shared_ptr<SceneRunner> b = *registry_.Find("b");
  NullSink device_a1, device_a2, device_b, viewer_a, viewer_b;
  ASSERT_TRUE(a->AttachDevice(&device_a1, {"probe", EffectSet::Default()}).ok());
  ASSERT_TRUE(a->AttachDevice(&device_a2, {"stylus", EffectSet::Default()}).ok());
  ASSERT_TRUE(b->AttachDevice(&device_b, {"probe", EffectSet::Default()}).ok());
  ASSERT_TRUE(a->AttachViewer(&viewer_a, EffectSet::Default()).ok());
  ASSERT_TRUE(b->AttachViewer(&viewer_b, EffectSet::Default()).ok());
  b->Detach(&device_b);
  const ServerActivity activity = ActivityOf(registry_, "");
  EXPECT_EQ(activity.devices, 2);
  EXPECT_EQ(activity.viewers, 2);
  EXPECT_EQ(activity.devices_joined, 3);
  EXPECT_EQ(activity.viewers_joined, 2);
  for (NullSink* sink : {&device_a1, &device_a2, &viewer_a}) a->Detach(sink);
  b->Detach(&viewer_b);
}

}  // namespace
}  // namespace hs

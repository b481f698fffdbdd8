#include "server/scene_registry.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "tests/common/scratch_dir.h"
#include "tests/server/test_server.h"

namespace hs::testing {
namespace {

class SceneRegistryTest : public ::testing::Test {
 protected:
  SceneRegistry& Registry(const ServerLimits& limits = {}) {
    registry_ = std::make_unique<SceneRegistry>(limits, ScratchDir("models").string(), metrics_);
    return *registry_;
  }
  Metrics metrics_;
  std::unique_ptr<SceneRegistry> registry_;
};

// Scenes are found by name once created, listed by name, and gone once
// deleted; a taken name is ALREADY_EXISTS, a missing one NOT_FOUND.
TEST_F(SceneRegistryTest, CreateFindListDelete) {
  SceneRegistry& registry = Registry();
  ASSERT_TRUE(registry.Create(SmallScene("b"), "").ok());
  ASSERT_TRUE(registry.Create(SmallScene("a"), "").ok());
  EXPECT_EQ(registry.Create(SmallScene("a"), "").status().code(), absl::StatusCode::kAlreadyExists);
  ASSERT_TRUE(registry.Find("a").ok());
  const std::vector<std::shared_ptr<SceneRunner>> listed = registry.List();
  ASSERT_EQ(listed.size(), 2u);
  EXPECT_EQ(listed[0]->spec().name(), "a");
  EXPECT_EQ(listed[1]->spec().name(), "b");
  EXPECT_TRUE(registry.Delete("a").ok());
  EXPECT_EQ(registry.Find("a").status().code(), absl::StatusCode::kNotFound);
  EXPECT_EQ(registry.Delete("a").code(), absl::StatusCode::kNotFound);
}

// An edit that fails (in the edit itself, in the build, past a limit, or
// by renaming) leaves the spec and revision as they were; one that works
// swaps the rebuilt scene in and bumps the revision.
TEST_F(SceneRegistryTest, FailedEditsChangeNothing) {
  ServerLimits limits;
  limits.max_objects_per_scene = 2;
  SceneRegistry& registry = Registry(limits);
  ASSERT_TRUE(registry.Create(SmallScene("s"), "").ok());
  const pb::SceneSpec before = (*registry.Find("s"))->spec();
  const int64_t revision = (*registry.Find("s"))->Info().revision;
  const std::vector<SceneRegistry::SpecEdit> failing = {
      [](pb::SceneSpec&) { return absl::InvalidArgumentError("no"); },
      [](pb::SceneSpec& spec) {
        spec.mutable_objects(0)->mutable_pose()->mutable_position_m()->set_x(std::nan(""));
        return absl::OkStatus();
      },
      [](pb::SceneSpec& spec) {
        *spec.add_objects() = spec.objects(1);
        spec.mutable_objects(2)->set_name("third");
        return absl::OkStatus();
      },
      [](pb::SceneSpec& spec) {
        spec.set_name("renamed");
        return absl::OkStatus();
      },
  };
  for (const SceneRegistry::SpecEdit& edit : failing) {
    EXPECT_FALSE(registry.Edit("s", edit).ok());
    EXPECT_EQ((*registry.Find("s"))->spec().DebugString(), before.DebugString());
    EXPECT_EQ((*registry.Find("s"))->Info().revision, revision);
  }
  absl::StatusOr<RunnerInfo> edited = registry.Edit("s", [](pb::SceneSpec& spec) {
    spec.mutable_objects(0)->mutable_pose()->mutable_position_m()->set_x(0.5);
    return absl::OkStatus();
  });
  ASSERT_TRUE(edited.ok()) << edited.status();
  EXPECT_EQ(edited->revision, revision + 1);
  EXPECT_EQ(edited->spec.objects(0).pose().position_m().x(), 0.5);
  EXPECT_EQ(
      registry.Edit("missing", [](pb::SceneSpec&) { return absl::OkStatus(); }).status().code(),
      absl::StatusCode::kNotFound);
}

// Past max_scenes and max_clients: RESOURCE_EXHAUSTED; a client slot given
// back can be taken again; after StopAll nothing more is created.
TEST_F(SceneRegistryTest, ServerWideLimitsAndStop) {
  ServerLimits limits;
  limits.max_scenes = 1;
  limits.max_clients = 1;
  SceneRegistry& registry = Registry(limits);
  ASSERT_TRUE(registry.Create(SmallScene("one"), "").ok());
  EXPECT_EQ(registry.Create(SmallScene("two"), "").status().code(),
            absl::StatusCode::kResourceExhausted);
  ASSERT_TRUE(registry.AddClient().ok());
  EXPECT_EQ(registry.AddClient().code(), absl::StatusCode::kResourceExhausted);
  registry.RemoveClient();
  EXPECT_TRUE(registry.AddClient().ok());
  registry.StopAll(absl::UnavailableError("stopping"));
  EXPECT_TRUE(registry.List().empty());
  EXPECT_EQ(registry.Create(SmallScene("three"), "").status().code(),
            absl::StatusCode::kUnavailable);
}

// With --record-scenes requested, only scenes whose spec sets `record`
// are recorded; a server without --record-dir refuses such a scene.
TEST_F(SceneRegistryTest, RecordsTheScenesThatAsk) {
  RecordingOptions recording;
  recording.dir = ScratchDir("requested_recordings").string();
  recording.all_scenes = false;
  SceneRegistry registry({}, ScratchDir("models").string(), metrics_, nullptr, recording);
  ASSERT_TRUE(registry.Create(SmallScene("quiet"), "").ok());
  pb::SceneSpec asks = SmallScene("recorded");
  asks.set_record(true);
  ASSERT_TRUE(registry.Create(asks, "").ok());
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(recording.dir)) {
    files.push_back(entry.path().filename().string());
  }
  ASSERT_EQ(files.size(), 1u);
  EXPECT_TRUE(files[0].starts_with("recorded_")) << files[0];

  SceneRegistry& plain = Registry();
  EXPECT_EQ(plain.Create(asks, "").status().code(), absl::StatusCode::kFailedPrecondition);
  EXPECT_FALSE(plain.Find("recorded").ok());
}

}  // namespace
}  // namespace hs::testing

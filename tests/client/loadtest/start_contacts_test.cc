#include "client/loadtest/start_contacts.h"

#include <gtest/gtest.h>

#include "client/loadtest/loadtest_scene.h"
#include "common/api/proto_convert.h"

namespace hs::cli {

// The built-in scene's copies of its 2 cm probe, each turned about world z
// on a ring of 10 cm radius: a copy's inner corners (9 cm out, 1 cm to
// either side) reach the next copy's when the copies are 2 atan(1/9) =
// 12.68 degrees apart, so 28 copies (12.86 degrees) fit and 29 (12.41) do
// not, each then touching both neighbours: as many pairs as copies. The
// pairs of tools_meet start 6 cm apart.
TEST(StartContactsTest, CopiesTouchPastWhatTheRingHolds) {
  for (const int clients : {1, 16, 28}) {
    const absl::StatusOr<haptics::v1::SceneSpec> spec =
        LoadtestScene(BuiltInLoadScene(), clients, "apart");
    ASSERT_TRUE(spec.ok()) << spec.status();
    EXPECT_EQ(ToolPairsTouchingAtStart(*spec, ""), 0) << clients;
  }
  for (const int clients : {29, 32}) {
    const absl::StatusOr<haptics::v1::SceneSpec> spec =
        LoadtestScene(BuiltInLoadScene(), clients, "crowded");
    ASSERT_TRUE(spec.ok()) << spec.status();
    EXPECT_EQ(ToolPairsTouchingAtStart(*spec, ""), clients) << clients;
  }
  const absl::StatusOr<haptics::v1::SceneSpec> pairs =
      LoadtestScene(BuiltInLoadScene(), 8, "meet", /*tools_meet=*/true);
  ASSERT_TRUE(pairs.ok()) << pairs.status();
  EXPECT_EQ(ToolPairsTouchingAtStart(*pairs, ""), 0);
}

// Two copies put in the same place touch: one pair.
TEST(StartContactsTest, ToolsInOnePlaceTouch) {
  absl::StatusOr<haptics::v1::SceneSpec> spec = LoadtestScene(BuiltInLoadScene(), 2, "same");
  ASSERT_TRUE(spec.ok()) << spec.status();
  const int n = spec->objects_size();
  *spec->mutable_objects(n - 1)->mutable_pose() = spec->objects(n - 2).pose();
  EXPECT_EQ(ToolPairsTouchingAtStart(*spec, ""), 1);
}

// A scene this side cannot build (a model file that is not there) is not
// known: -1, not 0.
TEST(StartContactsTest, UnbuildableSceneIsUnknown) {
  absl::StatusOr<haptics::v1::SceneSpec> spec = LoadtestScene(BuiltInLoadScene(), 2, "missing");
  ASSERT_TRUE(spec.ok()) << spec.status();
  spec->mutable_objects(0)->mutable_model()->set_path("no_such_model.obj");
  EXPECT_EQ(ToolPairsTouchingAtStart(*spec, "/nonexistent"), -1);
}

}  // namespace hs::cli

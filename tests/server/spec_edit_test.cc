#include "server/spec_edit.h"

#include <gtest/gtest.h>

namespace hs {
namespace {

namespace pb = haptics::v1;

pb::SceneSpec TwoObjects() {
  pb::SceneSpec spec;
  spec.set_name("s");
  spec.add_objects()->set_name("a");
  spec.add_objects()->set_name("b");
  return spec;
}

// Edits find objects by name: unknown names are NOT_FOUND, taken names
// ALREADY_EXISTS, and a failed edit leaves the spec as it was.
TEST(SpecEditTest, NamesAndFailuresLeaveSpec) {
  pb::SceneSpec spec = TwoObjects();
  pb::SceneObject a;
  a.set_name("a");
  EXPECT_EQ(AddObjectToSpec(a, spec).code(), absl::StatusCode::kAlreadyExists);
  EXPECT_EQ(RemoveObjectFromSpec("c", spec).code(), absl::StatusCode::kNotFound);
  pb::UpdateObjectRequest update;
  update.set_object("c");
  EXPECT_EQ(UpdateObjectInSpec(update, spec).code(), absl::StatusCode::kNotFound);
  EXPECT_EQ(spec.SerializeAsString(), TwoObjects().SerializeAsString());

  ASSERT_TRUE(RemoveObjectFromSpec("a", spec).ok());
  ASSERT_EQ(spec.objects_size(), 1);
  EXPECT_EQ(spec.objects(0).name(), "b");
}

// An update sets the pose when given, replaces materials only when asked,
// and appends vertex moves.
TEST(SpecEditTest, UpdateFields) {
  pb::SceneSpec spec = TwoObjects();
  spec.mutable_objects(1)->add_materials()->set_face_group("skin");
  pb::UpdateObjectRequest update;
  update.set_object("b");
  update.mutable_pose()->mutable_position_m()->set_z(2);
  update.add_vertex_moves()->set_vertex_id(3);
  ASSERT_TRUE(UpdateObjectInSpec(update, spec).ok());
  ASSERT_TRUE(UpdateObjectInSpec(update, spec).ok());
  EXPECT_EQ(spec.objects(1).pose().position_m().z(), 2);
  EXPECT_EQ(spec.objects(1).materials_size(), 1);
  EXPECT_EQ(spec.objects(1).vertex_moves_size(), 2);
  update.set_set_materials(true);
  ASSERT_TRUE(UpdateObjectInSpec(update, spec).ok());
  EXPECT_EQ(spec.objects(1).materials_size(), 0);
}

// Clients may not name files on the server; scene files' relative paths
// become absolute against their folder.
TEST(SpecEditTest, ModelPaths) {
  pb::SceneSpec spec = TwoObjects();
  EXPECT_TRUE(RejectModelPaths(spec).ok());
  spec.mutable_objects(0)->mutable_model()->set_path("organ.obj");
  EXPECT_EQ(RejectModelPaths(spec).code(), absl::StatusCode::kPermissionDenied);
  AbsoluteModelPaths("/data/scenes", spec);
  EXPECT_EQ(spec.objects(0).model().path(), "/data/scenes/organ.obj");
}

}  // namespace
}  // namespace hs

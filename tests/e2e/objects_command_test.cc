#include "client/objects_command.h"

#include <gtest/gtest.h>

#include <sstream>

#include "client/exit_codes.h"
#include "tests/server/test_server.h"

namespace hs::cli {
namespace {

class ObjectsCommandTest : public ::testing::Test {
 protected:
  ObjectsCommandTest() { server_.Create(hs::testing::SmallScene("s")); }

  ObjectsArgs Args(const std::string& action, const std::string& object) {
    ObjectsArgs args;
    args.server.address = server_.address();
    args.action = action;
    args.scene = "s";
    args.object = object;
    return args;
  }

  hs::testing::TestServer server_;
  std::ostringstream out_, err_;
};

// add, update and remove change the scene's spec as asked, each with exit 0.
TEST_F(ObjectsCommandTest, AddUpdateRemove) {
  ObjectsArgs add = Args("add", "ball");
  add.sphere_radius_m = 0.03;
  add.pose = "0.05,0,0.1,0,0,0";
  ASSERT_EQ(RunObjects(add, out_, err_), kExitOk) << err_.str();
  EXPECT_EQ(server_.Get("s").spec().objects_size(), 3);
  EXPECT_EQ(server_.Get("s").spec().objects(2).pose().position_m().z(), 0.1);

  ObjectsArgs update = Args("update", "table");
  update.pose = "0,0,-0.01,0,0,0";
  update.material = "500,0.1,0.5,0.4";
  update.vertex_moves = {"0:-0.1,-0.1,-0.02"};
  ASSERT_EQ(RunObjects(update, out_, err_), kExitOk) << err_.str();
  const haptics::v1::SceneObject table = server_.Get("s").spec().objects(0);
  EXPECT_EQ(table.pose().position_m().z(), -0.01);
  ASSERT_EQ(table.materials_size(), 1);
  EXPECT_EQ(table.materials(0).material().stiffness_n_per_m(), 500);
  ASSERT_EQ(table.vertex_moves_size(), 1);

  ASSERT_EQ(RunObjects(Args("remove", "ball"), out_, err_), kExitOk) << err_.str();
  EXPECT_EQ(server_.Get("s").spec().objects_size(), 2);
}

// A free body is added as one and listed with its kind.
TEST_F(ObjectsCommandTest, AddsAFreeBodyAndListsItsKind) {
  ObjectsArgs add = Args("add", "pebble");
  add.kind = "free";
  add.box = "0.02,0.02,0.02";
  add.pose = "0,0,0.3,0,0,0";
  ASSERT_EQ(RunObjects(add, out_, err_), kExitOk) << err_.str();
  const haptics::v1::SceneSpec spec = server_.Get("s").spec();
  ASSERT_EQ(spec.objects_size(), 3);
  EXPECT_EQ(spec.objects(2).kind(), haptics::v1::OBJECT_KIND_FREE);
  EXPECT_NE(out_.str().find("  pebble (free) at (0, 0, 0.3) m\n"), std::string::npos) << out_.str();
}

// Refusals, unknown names and bad local values each have their exit status.
TEST_F(ObjectsCommandTest, ExitStatusesOfFailures) {
  ObjectsArgs taken = Args("add", "table");
  taken.box = "0.1,0.1,0.1";
  EXPECT_EQ(RunObjects(taken, out_, err_), kExitRefused);
  ObjectsArgs bad_vertex = Args("update", "table");
  bad_vertex.vertex_moves = {"100000:0,0,0"};
  EXPECT_EQ(RunObjects(bad_vertex, out_, err_), kExitRefused);
  EXPECT_NE(err_.str().find("INVALID_ARGUMENT: "), std::string::npos) << err_.str();
  EXPECT_EQ(RunObjects(Args("remove", "nope"), out_, err_), kExitNotFound);
  ObjectsArgs no_shape = Args("add", "thing");
  EXPECT_EQ(RunObjects(no_shape, out_, err_), kExitFailure);
  ObjectsArgs bad_pose = Args("update", "table");
  bad_pose.pose = "0,0,nan,0,0,0";
  EXPECT_EQ(RunObjects(bad_pose, out_, err_), kExitFailure);
  EXPECT_EQ(server_.Get("s").revision(), 0);
}

}  // namespace
}  // namespace hs::cli

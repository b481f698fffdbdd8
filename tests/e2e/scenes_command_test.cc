#include "client/scenes_command.h"

#include <gtest/gtest.h>

#include <sstream>

#include "client/exit_codes.h"
#include "tests/common/test_data_dir.h"
#include "tests/server/test_server.h"

namespace hs::cli {
namespace {

const std::string kDemoScene = hs::ScenesDir() + "/probe_on_torus.textproto";

class ScenesCommandTest : public ::testing::Test {
 protected:
  int Run(const std::string& action, const std::string& name = "", const std::string& file = "") {
    ScenesArgs args;
    args.server.address = server_.address();
    args.action = action;
    args.name = name;
    args.scene_file = file;
    out_.str("");
    err_.str("");
    return RunScenes(args, out_, err_);
  }

  hs::testing::TestServer server_;
  std::ostringstream out_, err_;
};

// A scene file goes through create, list, show and delete, each with exit 0,
// and the server holds exactly what was created.
TEST_F(ScenesCommandTest, Lifecycle) {
  ASSERT_EQ(Run("create", "demo", kDemoScene), kExitOk) << err_.str();
  EXPECT_EQ(server_.Get("demo").spec().objects_size(), 3);
  ASSERT_EQ(Run("list"), kExitOk);
  EXPECT_NE(out_.str().find("demo: step"), std::string::npos) << out_.str();
  ASSERT_EQ(Run("show", "demo"), kExitOk);
  EXPECT_NE(out_.str().find("organ (fixed)"), std::string::npos) << out_.str();
  EXPECT_NE(out_.str().find("probe (tool)"), std::string::npos);
  ASSERT_EQ(Run("delete", "demo"), kExitOk);
  ASSERT_EQ(Run("list"), kExitOk);
  EXPECT_EQ(out_.str(), "");
}

// Each failure has its exit status and names the gRPC code on stderr.
TEST_F(ScenesCommandTest, ExitStatusesOfFailures) {
  ASSERT_EQ(Run("create", "demo", kDemoScene), kExitOk);
  EXPECT_EQ(Run("create", "demo", kDemoScene), kExitRefused);
  EXPECT_NE(err_.str().find("ALREADY_EXISTS: "), std::string::npos) << err_.str();
  EXPECT_EQ(Run("show", "nope"), kExitNotFound);
  EXPECT_NE(err_.str().find("NOT_FOUND: "), std::string::npos) << err_.str();
  EXPECT_EQ(Run("delete", "nope"), kExitNotFound);
  EXPECT_EQ(Run("create", "x", "/nonexistent.textproto"), kExitFailure);
  ScenesArgs unreachable;
  unreachable.server.address = "127.0.0.1:1";
  unreachable.action = "list";
  EXPECT_EQ(RunScenes(unreachable, out_, err_), kExitUnavailable);
  EXPECT_NE(err_.str().find("UNAVAILABLE: "), std::string::npos) << err_.str();
}

// --json prints one SceneInfo per line, with the proto field names.
TEST_F(ScenesCommandTest, JsonLines) {
  server_.Create(hs::testing::SmallScene("a"));
  server_.Create(hs::testing::SmallScene("b"));
  ScenesArgs args;
  args.server.address = server_.address();
  args.action = "list";
  args.json = true;
  ASSERT_EQ(RunScenes(args, out_, err_), kExitOk);
  EXPECT_EQ(out_.str().find("{\"spec\":{\"name\":\"a\"},"), 0u) << out_.str();
  EXPECT_NE(out_.str().find("\n{\"spec\":{\"name\":\"b\"},"), std::string::npos);
  const std::string text = out_.str();
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 2);
}

}  // namespace
}  // namespace hs::cli

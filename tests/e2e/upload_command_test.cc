#include "client/upload_command.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "client/delete_model_command.h"
#include "client/exit_codes.h"
#include "client/objects_command.h"
#include "tests/common/scratch_dir.h"
#include "tests/common/test_data_dir.h"
#include "tests/server/test_server.h"

namespace hs::cli {
namespace {

const std::string kData = hs::TestDataDir();

// An uploaded model (in small chunks) gets an id that an added object can
// use; a malformed model and a taken name are refused, a missing file fails.
TEST(UploadCommandTest, UploadAndUse) {
  hs::testing::TestServer server;
  server.Create(hs::testing::SmallScene("s"));
  std::ostringstream out, err;
  UploadArgs args;
  args.server.address = server.address();
  args.file = kData + "/cube.obj";
  args.chunk_bytes = 100;
  ASSERT_EQ(RunUpload(args, out, err), kExitOk) << err.str();
  EXPECT_EQ(out.str().substr(0, out.str().find(' ')), "cube.obj");

  ObjectsArgs add;
  add.server.address = server.address();
  add.action = "add";
  add.scene = "s";
  add.object = "block";
  add.model_id = "cube.obj";
  add.pose = "0,0,0.2,0,0,0";
  ASSERT_EQ(RunObjects(add, out, err), kExitOk) << err.str();
  EXPECT_EQ(server.Get("s").spec().objects_size(), 3);

  // The same bytes again are the stored model; other bytes under its id
  // are refused.
  EXPECT_EQ(RunUpload(args, out, err), kExitOk) << err.str();
  const std::filesystem::path other = hs::ScratchDir("other") / "cube.obj";
  std::ofstream(other)
      << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  args.file = other.string();
  EXPECT_EQ(RunUpload(args, out, err), kExitRefused);
  EXPECT_NE(err.str().find("ALREADY_EXISTS: model 'cube.obj' exists with other content"),
            std::string::npos)
      << err.str();
  // delete-model: refused while scene "s" uses it, done once it does not.
  DeleteModelArgs remove;
  remove.server.address = server.address();
  remove.model_id = "cube.obj";
  EXPECT_EQ(RunDeleteModel(remove, out, err), kExitRefused);
  EXPECT_NE(err.str().find("FAILED_PRECONDITION: model 'cube.obj' is used by object 'block'"),
            std::string::npos)
      << err.str();
  ObjectsArgs drop;
  drop.server.address = server.address();
  drop.action = "remove";
  drop.scene = "s";
  drop.object = "block";
  ASSERT_EQ(RunObjects(drop, out, err), kExitOk) << err.str();
  EXPECT_EQ(RunDeleteModel(remove, out, err), kExitOk) << err.str();
  EXPECT_EQ(RunDeleteModel(remove, out, err), kExitNotFound);
  EXPECT_EQ(RunUpload(args, out, err), kExitOk) << err.str();  // the id is free again

  args.file = kData + "/garbage.obj";
  EXPECT_EQ(RunUpload(args, out, err), kExitRefused);
  args.file = kData + "/no_such_file.obj";
  EXPECT_EQ(RunUpload(args, out, err), kExitFailure);
}

}  // namespace
}  // namespace hs::cli

#include "client/delete_model_command.h"

#include <gtest/gtest.h>

#include <sstream>

#include "client/exit_codes.h"
#include "client/upload_command.h"
#include "tests/common/test_data_dir.h"
#include "tests/server/test_server.h"

namespace hs::cli {
namespace {

const std::string kData = hs::TestDataDir();

// An uploaded model no scene uses is deleted, saying so; a second delete
// finds nothing (exit kExitNotFound, the server's status on stderr). The
// refusal while a scene uses the model is in upload_command_test.
TEST(DeleteModelCommandTest, DeletesOnce) {
  hs::testing::TestServer server;
  std::ostringstream out, err;
  UploadArgs upload;
  upload.server.address = server.address();
  upload.file = kData + "/cube.obj";
  ASSERT_EQ(RunUpload(upload, out, err), kExitOk) << err.str();
  DeleteModelArgs args;
  args.server.address = server.address();
  args.model_id = "cube.obj";
  std::ostringstream deleted;
  EXPECT_EQ(RunDeleteModel(args, deleted, err), kExitOk) << err.str();
  EXPECT_EQ(deleted.str(), "deleted cube.obj\n");
  std::ostringstream again_out, again_err;
  EXPECT_EQ(RunDeleteModel(args, again_out, again_err), kExitNotFound);
  EXPECT_NE(again_err.str().find("NOT_FOUND"), std::string::npos) << again_err.str();
  EXPECT_EQ(again_out.str(), "");
}

// No server listening is kExitUnavailable.
TEST(DeleteModelCommandTest, NoServerIsUnavailable) {
  std::string address;
  {
    hs::testing::TestServer gone;
    address = gone.address();
  }
  DeleteModelArgs args;
  args.server.address = address;
  args.server.timeout_s = 2;
  args.model_id = "cube.obj";
  std::ostringstream out, err;
  EXPECT_EQ(RunDeleteModel(args, out, err), kExitUnavailable) << err.str();
}

}  // namespace
}  // namespace hs::cli

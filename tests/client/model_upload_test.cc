#include "client/model_upload.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "tests/common/test_data_dir.h"
#include "tests/server/test_server.h"

namespace hs::cli {
namespace {

TEST(ModelUploadTest, NamesAndFormatsComeFromTheFile) {
  // The stem, made safe and at most 64 characters; the extension without
  // its dot.
  EXPECT_EQ(DefaultModelName("models/liver v2.obj"), "liver_v2");
  EXPECT_EQ(DefaultModelName("a-b_c.d.stl"), "a-b_c.d");
  EXPECT_EQ(DefaultModelName(std::string(80, 'x') + ".ply"), std::string(64, 'x'));
  EXPECT_EQ(ModelFormat("models/liver.obj"), "obj");
  EXPECT_EQ(ModelFormat("README"), "");
}

TEST(ModelUploadTest, UploadsInChunks) {
  // The unit cube OBJ sent 100 bytes at a time is stored whole: 8
  // vertices, 12 triangles, under "<name>.<format>".
  testing::TestServer server;
  std::ifstream in(hs::TestDataDir() + "/cube.obj");
  std::ostringstream bytes;
  bytes << in.rdbuf();
  haptics::v1::UploadModelResponse response;
  const grpc::Status status =
      UploadModelBytes(server.scenes(), bytes.str(), "cube", "obj", 100, 10, &response);
  ASSERT_TRUE(status.ok()) << status.error_message();
  EXPECT_EQ(response.model_id(), "cube.obj");
  EXPECT_EQ(response.vertices(), 8);
  EXPECT_EQ(response.triangles(), 12);
}

TEST(ModelUploadTest, AnUnreadableModelIsRefused) {
  // Bytes that are no OBJ: the server refuses them, and says so.
  testing::TestServer server;
  haptics::v1::UploadModelResponse response;
  const grpc::Status status =
      UploadModelBytes(server.scenes(), "not a mesh\n", "junk", "obj", 1 << 20, 10, &response);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << status.error_message();
}

}  // namespace
}  // namespace hs::cli

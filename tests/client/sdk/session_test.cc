// The C++ SDK's Session through libhaptics_client, against the built
// haptic-server.
#include "haptics/client.h"

#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <fstream>
#include <string>

#include "tests/common/scratch_dir.h"
#include "tests/common/test_certificates.h"
#include "tests/common/test_data_dir.h"
#include "tests/server/server_process.h"

namespace {

using haptics::Code;
using haptics::Session;

// A table and a probe: a SceneSpec in text format, and the same in JSON.
constexpr char kSceneText[] = R"(name: "bench"
step_s: 0.001
objects {
  name: "table"
  kind: OBJECT_KIND_FIXED
  model { procedural { box { size_m { x: 0.2 y: 0.2 z: 0.02 } } } }
}
objects {
  name: "probe"
  kind: OBJECT_KIND_TOOL
  model { procedural { box { size_m { x: 0.02 y: 0.02 z: 0.02 } } } }
  pose { position_m { z: 0.05 } }
}
)";
constexpr char kSceneJson[] = R"({"name": "bench json", "stepS": 0.001, "objects": [
  {"name": "probe", "kind": "OBJECT_KIND_TOOL",
   "model": {"procedural": {"sphere": {"radiusM": 0.01}}}}]})";

std::string Write(const std::filesystem::path& dir, const std::string& name,
                  const std::string& text) {
  const std::filesystem::path path = dir / name;
  std::ofstream(path) << text;
  return path.string();
}

class SessionTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_GT(server_.port(), 0) << server_.startup();
    auto session = Session::Connect("127.0.0.1:" + std::to_string(server_.port()));
    ASSERT_TRUE(session.ok()) << session.error().ToString();
    session_ = *std::move(session);
  }

  std::vector<std::string> SceneNames() {
    auto scenes = session_->ListScenes();
    EXPECT_TRUE(scenes.ok()) << scenes.error().ToString();
    std::vector<std::string> names;
    if (scenes.ok()) {
      for (const haptics::SceneInfo& info : *scenes) names.push_back(info.name);
    }
    std::sort(names.begin(), names.end());
    return names;
  }

  hs::testing::ServerProcess server_;
  std::unique_ptr<Session> session_;
};

TEST_F(SessionTest, HealthIsServing) {
  // The server's grpc.health.v1 status, by name.
  auto health = session_->Health();
  ASSERT_TRUE(health.ok()) << health.error().ToString();
  EXPECT_EQ(*health, "SERVING");
}

TEST_F(SessionTest, ScenesFromFilesAreCreatedReplacedAndDeleted) {
  // Text and JSON SceneSpec files make scenes (under another name when
  // asked); a name taken is ALREADY_EXISTS, replacing is not; deleting
  // twice is NOT_FOUND the second time.
  const std::filesystem::path dir = hs::ScratchDir("sdk_session");
  const std::string text = Write(dir, "bench.textproto", kSceneText);
  const std::string json = Write(dir, "bench.json", kSceneJson);
  auto created = session_->CreateScene(text);
  ASSERT_TRUE(created.ok()) << created.error().ToString();
  EXPECT_EQ(created->name, "bench");
  EXPECT_EQ(created->step_s, 0.001);
  ASSERT_TRUE(session_->CreateScene(json).ok());
  ASSERT_TRUE(session_->CreateScene(text, "bench copy").ok());
  EXPECT_EQ(SceneNames(),
            (std::vector<std::string>{"bench", "bench copy", "bench json", "probe on torus"}));
  auto again = session_->CreateScene(text);
  ASSERT_FALSE(again.ok());
  EXPECT_EQ(again.error().code, Code::kAlreadyExists);
  EXPECT_EQ(again.error().ToString().rfind("ALREADY_EXISTS: ", 0), 0u);
  auto replaced = session_->ReplaceScene(text);
  ASSERT_TRUE(replaced.ok()) << replaced.error().ToString();
  EXPECT_TRUE(session_->DeleteScene("bench copy").ok());
  const haptics::Error twice = session_->DeleteScene("bench copy");
  EXPECT_EQ(twice.code, Code::kNotFound);
  EXPECT_NE(twice.message.find("bench copy"), std::string::npos);
  EXPECT_EQ(SceneNames(), (std::vector<std::string>{"bench", "bench json", "probe on torus"}));
}

TEST_F(SessionTest, UnreadableSceneFilesAreRefusedHere) {
  // A missing file is NOT_FOUND and one that does not parse
  // INVALID_ARGUMENT, both naming the file; the server is not asked.
  auto missing = session_->CreateScene("no/such/scene.textproto");
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.error().code, Code::kNotFound);
  EXPECT_NE(missing.error().message.find("no/such/scene.textproto"), std::string::npos);
  const std::string bad = Write(hs::ScratchDir("sdk_session"), "bad.textproto",
                                "name: \"x\" objects { nonsense: 1 }\n");
  auto invalid = session_->CreateScene(bad);
  ASSERT_FALSE(invalid.ok());
  EXPECT_EQ(invalid.error().code, Code::kInvalidArgument);
  EXPECT_NE(invalid.error().message.find("bad.textproto"), std::string::npos);
  EXPECT_EQ(SceneNames(), (std::vector<std::string>{"probe on torus"}));
}

TEST_F(SessionTest, ModelsAreUploadedAndDeleted) {
  // The unit cube OBJ (8 vertices, 12 triangles) uploads under the file's
  // stem; deleting it twice is NOT_FOUND the second time.
  auto model = session_->UploadModel(hs::TestDataDir() + "/cube.obj");
  ASSERT_TRUE(model.ok()) << model.error().ToString();
  EXPECT_EQ(model->model_id, "cube.obj");
  EXPECT_EQ(model->vertices, 8);
  EXPECT_EQ(model->triangles, 12);
  EXPECT_TRUE(session_->DeleteModel(model->model_id).ok());
  EXPECT_EQ(session_->DeleteModel(model->model_id).code, Code::kNotFound);
}

TEST_F(SessionTest, CallsAfterTheServerEndsAreUnavailable) {
  // Requests on a session whose server has gone fail UNAVAILABLE.
  server_.StopWith(SIGKILL);
  auto scenes = session_->ListScenes();
  ASSERT_FALSE(scenes.ok());
  EXPECT_EQ(scenes.error().code, Code::kUnavailable);
}

TEST(SessionTlsTest, ConnectsWithTheRightCertificatesOnly) {
  // Over TLS with a client certificate the session works; without the
  // certificate, or expecting another server name, it does not connect.
  const hs::TestCertificates& c = hs::MakeTestCertificates();
  hs::testing::ServerProcess server({"--tls-cert", c.server_cert.string(), "--tls-key",
                                     c.server_key.string(), "--tls-client-ca", c.ca.string()});
  ASSERT_GT(server.port(), 0) << server.startup();
  const std::string address = "127.0.0.1:" + std::to_string(server.port());
  haptics::SessionOptions tls;
  tls.tls = {.ca_file = c.ca.string(),
             .cert_file = c.client_cert.string(),
             .key_file = c.client_key.string(),
             .server_name = "localhost"};
  auto session = Session::Connect(address, tls);
  ASSERT_TRUE(session.ok()) << session.error().ToString();
  auto health = (*session)->Health();
  ASSERT_TRUE(health.ok()) << health.error().ToString();
  EXPECT_EQ(*health, "SERVING");

  // A refused handshake is only seen as no connection within the timeout.
  tls.connect_timeout_s = 1;
  haptics::SessionOptions no_certificate = tls;
  no_certificate.tls.cert_file.clear();
  no_certificate.tls.key_file.clear();
  auto refused = Session::Connect(address, no_certificate);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().code, Code::kUnavailable);

  haptics::SessionOptions wrong_name = tls;
  wrong_name.tls.server_name = "elsewhere.example";
  auto mismatched = Session::Connect(address, wrong_name);
  ASSERT_FALSE(mismatched.ok());
  EXPECT_EQ(mismatched.error().code, Code::kUnavailable);
}

}  // namespace

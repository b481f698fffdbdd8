#include "server/auth/access_policy.h"

#include <gtest/gtest.h>

#include <thread>

#include <fstream>
#include <map>

#include "absl/strings/escaping.h"
#include "common/hash/sha256.h"
#include "server/haptic_server.h"
#include "tests/common/scratch_dir.h"
#include "tests/server/test_server.h"

namespace hs::testing {
namespace {

std::string Digest(const std::string& token) {
  Sha256 hash;
  hash.Update(token);
  return absl::BytesToHexString(hash.Finish());
}

// A server checking tokens from a file this fixture writes: an admin of
// every scene, a driver and a watcher of scenes "train-*".
class AccessPolicyTest : public ::testing::Test {
 protected:
  void SetUp() override {
    tokens_file_ = (ScratchDir("tokens") / "tokens").string();
    WriteTokens({{"admin-token", "admin * instructor"},
                 {"drive-token", "drive train-* trainee"},
                 {"watch-token", "watch train-*"}});
    ServerOptions options;
    options.listen = "127.0.0.1:0";
    options.tokens_file = tokens_file_;
    absl::StatusOr<std::unique_ptr<HapticServer>> server = HapticServer::Start(options, metrics_);
    ASSERT_TRUE(server.ok()) << server.status();
    server_ = *std::move(server);
    auto channel = grpc::CreateChannel("127.0.0.1:" + std::to_string(server_->port()),
                                       grpc::InsecureChannelCredentials());
    scenes_ = pb::SceneService::NewStub(channel);
    sessions_ = pb::SessionService::NewStub(channel);
    for (const char* name : {"train-1", "exam-1"}) {
      pb::CreateSceneRequest request;
      *request.mutable_spec() = SmallScene(name);
      pb::SceneInfo info;
      ASSERT_TRUE(scenes_->CreateScene(As("admin-token").get(), request, &info).ok());
    }
  }
  void TearDown() override {
    if (server_) server_->Shutdown(0.5);
  }

  void WriteTokens(const std::vector<std::pair<std::string, std::string>>& lines) {
    std::ofstream out(tokens_file_);
    for (const auto& [token, grant] : lines)
      out << "sha256:" << Digest(token) << " " << grant << "\n";
  }

  // A context carrying `authorization` as given ("" sends none).
  static std::unique_ptr<grpc::ClientContext> WithHeader(const std::string& authorization) {
    std::unique_ptr<grpc::ClientContext> context = ContextWithin(5);
    if (!authorization.empty()) context->AddMetadata("authorization", authorization);
    return context;
  }
  static std::unique_ptr<grpc::ClientContext> As(const std::string& token) {
    return WithHeader("Bearer " + token);
  }

  // The status of every unary and streaming method called with
  // `authorization` on scene `scene` (a scene that does not exist, so that
  // a call let through fails with NOT_FOUND and changes nothing).
  std::map<std::string, grpc::StatusCode> CallEach(const std::string& authorization,
                                                   const std::string& scene);

  Metrics metrics_;
  std::string tokens_file_;
  std::unique_ptr<HapticServer> server_;
  std::unique_ptr<pb::SceneService::Stub> scenes_;
  std::unique_ptr<pb::SessionService::Stub> sessions_;
};

std::map<std::string, grpc::StatusCode> AccessPolicyTest::CallEach(const std::string& authorization,
                                                                   const std::string& scene) {
  std::map<std::string, grpc::StatusCode> codes;
  pb::SceneInfo info;
  {
    pb::CreateSceneRequest request;
    *request.mutable_spec() = SmallScene(scene);
    request.mutable_spec()->set_step_s(-1);  // let through: INVALID_ARGUMENT
    codes["CreateScene"] =
        scenes_->CreateScene(WithHeader(authorization).get(), request, &info).error_code();
  }
  {
    pb::GetSceneRequest request;
    request.set_scene(scene);
    codes["GetScene"] =
        scenes_->GetScene(WithHeader(authorization).get(), request, &info).error_code();
  }
  {
    pb::ListScenesResponse response;
    codes["ListScenes"] =
        scenes_->ListScenes(WithHeader(authorization).get(), {}, &response).error_code();
  }
  {
    pb::DeleteSceneRequest request;
    request.set_scene(scene);
    pb::DeleteSceneResponse response;
    codes["DeleteScene"] =
        scenes_->DeleteScene(WithHeader(authorization).get(), request, &response).error_code();
  }
  {
    pb::AddObjectRequest request;
    request.set_scene(scene);
    *request.mutable_object() = SmallScene("x").objects(0);
    codes["AddObject"] =
        scenes_->AddObject(WithHeader(authorization).get(), request, &info).error_code();
  }
  {
    pb::UpdateObjectRequest request;
    request.set_scene(scene);
    request.set_object("table");
    codes["UpdateObject"] =
        scenes_->UpdateObject(WithHeader(authorization).get(), request, &info).error_code();
  }
  {
    pb::RemoveObjectRequest request;
    request.set_scene(scene);
    request.set_object("table");
    codes["RemoveObject"] =
        scenes_->RemoveObject(WithHeader(authorization).get(), request, &info).error_code();
  }
  {
    pb::SetEffectsRequest request;
    request.set_scene(scene);
    codes["SetEffects"] =
        scenes_->SetEffects(WithHeader(authorization).get(), request, &info).error_code();
  }
  {
    pb::DeleteModelRequest request;
    request.set_model_id("missing.obj");  // let through: NOT_FOUND
    pb::DeleteModelResponse response;
    codes["DeleteModel"] =
        scenes_->DeleteModel(WithHeader(authorization).get(), request, &response).error_code();
  }
  {
    pb::UploadModelResponse response;
    auto context = WithHeader(authorization);
    auto writer = scenes_->UploadModel(context.get(), &response);
    pb::UploadModelChunk chunk;
    chunk.mutable_header()->set_name("../bad name");  // let through: INVALID_ARGUMENT
    writer->Write(chunk);
    writer->WritesDone();
    codes["UploadModel"] = writer->Finish().error_code();
  }
  {
    pb::WatchRequest request;
    request.set_scene(scene);
    auto context = WithHeader(authorization);
    auto reader = sessions_->Watch(context.get(), request);
    pb::Frame frame;
    while (reader->Read(&frame)) {
    }
    codes["Watch"] = reader->Finish().error_code();
  }
  {
    auto context = WithHeader(authorization);
    auto stream = sessions_->Interact(context.get());
    pb::InteractRequest request;
    request.mutable_open()->set_scene(scene);
    request.mutable_open()->set_tool("probe");
    stream->Write(request);
    stream->WritesDone();
    pb::Frame frame;
    while (stream->Read(&frame)) {
    }
    codes["Interact"] = stream->Finish().error_code();
  }
  return codes;
}

// The documented role table: the least role of each method; every method
// but ListScenes, UploadModel and DeleteModel names a scene.
const std::map<std::string, Role>& LeastRoles() {
  static const auto* roles = new std::map<std::string, Role>{
      {"GetScene", Role::kWatch},   {"ListScenes", Role::kWatch},   {"Watch", Role::kWatch},
      {"Interact", Role::kDrive},   {"CreateScene", Role::kAdmin},  {"DeleteScene", Role::kAdmin},
      {"AddObject", Role::kAdmin},  {"UpdateObject", Role::kAdmin}, {"RemoveObject", Role::kAdmin},
      {"SetEffects", Role::kAdmin}, {"UploadModel", Role::kAdmin},  {"DeleteModel", Role::kAdmin}};
  return *roles;
}

// What a call let through by the policy ends with (the scene is missing or
// the request is bad on purpose).
grpc::StatusCode LetThrough(const std::string& method) {
  if (method == "ListScenes") return grpc::StatusCode::OK;
  if (method == "CreateScene" || method == "UploadModel") return grpc::StatusCode::INVALID_ARGUMENT;
  return grpc::StatusCode::NOT_FOUND;
}

// Without a token, with a malformed header or an unknown token, every
// method is UNAUTHENTICATED, streams included.
TEST_F(AccessPolicyTest, EveryMethodNeedsAKnownToken) {
  for (const std::string authorization :
       {"", "Bearer nobody", "Basic admin-token", "admin-token"}) {
    for (const auto& [method, code] : CallEach(authorization, "train-missing")) {
      EXPECT_EQ(code, grpc::StatusCode::UNAUTHENTICATED) << authorization << " " << method;
    }
  }
  EXPECT_EQ(LeastRoles().size(), CallEach("", "x").size());  // every method was called
}

// Each role gets exactly what the role table gives it, on the scenes its
// pattern matches; past them, PERMISSION_DENIED.
TEST_F(AccessPolicyTest, RolesAndScenePatternsAllowWhatTheTableSays) {
  const std::map<std::string, Role> tokens = {
      {"admin-token", Role::kAdmin}, {"drive-token", Role::kDrive}, {"watch-token", Role::kWatch}};
  for (const auto& [token, role] : tokens) {
    for (const std::string scene : {"train-missing", "exam-missing"}) {
      const bool scene_matches = role == Role::kAdmin || scene.starts_with("train-");
      for (const auto& [method, code] : CallEach("Bearer " + token, scene)) {
        const bool names_scene =
            method != "ListScenes" && method != "UploadModel" && method != "DeleteModel";
        const bool allowed = role >= LeastRoles().at(method) && (!names_scene || scene_matches);
        EXPECT_EQ(code, allowed ? LetThrough(method) : grpc::StatusCode::PERMISSION_DENIED)
            << token << " " << scene << " " << method;
      }
    }
  }
  // Nothing was changed by any of it.
  pb::ListScenesResponse all;
  ASSERT_TRUE(scenes_->ListScenes(As("admin-token").get(), {}, &all).ok());
  EXPECT_EQ(all.scenes_size(), 2);
}

// ListScenes shows a caller only the scenes its pattern matches; a driver
// drives a tool of a scene it may see.
TEST_F(AccessPolicyTest, CallersSeeAndDriveTheirScenesOnly) {
  pb::ListScenesResponse listed;
  ASSERT_TRUE(scenes_->ListScenes(As("watch-token").get(), {}, &listed).ok());
  ASSERT_EQ(listed.scenes_size(), 1);
  EXPECT_EQ(listed.scenes(0).spec().name(), "train-1");

  auto context = As("drive-token");
  auto stream = sessions_->Interact(context.get());
  pb::InteractRequest open;
  open.mutable_open()->set_scene("train-1");
  open.mutable_open()->set_tool("probe");
  ASSERT_TRUE(stream->Write(open));
  pb::Frame frame;
  EXPECT_TRUE(stream->Read(&frame));
  context->TryCancel();
  stream->Finish();
}

// An instructor (admin) takes a trainee's tool: the trainee's stream ends
// ABORTED naming who took it, and the instructor drives, as the frames
// say (each tool's holder, the token's NAME); a driver may not
// take over (PERMISSION_DENIED), nor may anyone take a tool the scene
// lacks (NOT_FOUND), and the holder keeps its tool; once the instructor
// leaves, the trainee takes the tool again.
TEST_F(AccessPolicyTest, AnInstructorTakesOverATool) {
  auto open = [&](bool take_over, grpc::ClientContext* context, const std::string& tool = "probe") {
    auto stream = sessions_->Interact(context);
    pb::InteractRequest request;
    request.mutable_open()->set_scene("train-1");
    request.mutable_open()->set_tool(tool);
    request.mutable_open()->set_take_over(take_over);
    EXPECT_TRUE(stream->Write(request));
    return stream;
  };
  pb::Frame frame;
  // The holder of `frame`'s probe, once the frames name one.
  auto holder_of_probe = [&](auto& stream) {
    for (int n = 0; n < 100 && stream->Read(&frame); ++n) {
      if (!frame.tools(0).holder().empty()) return frame.tools(0).holder();
    }
    return std::string();
  };
  auto trainee_context = As("drive-token");
  auto trainee = open(false, trainee_context.get());
  EXPECT_EQ(holder_of_probe(trainee), "trainee");

  auto rival_context = As("drive-token");
  auto rival = open(true, rival_context.get());
  while (rival->Read(&frame)) {
  }
  EXPECT_EQ(rival->Finish().error_code(), grpc::StatusCode::PERMISSION_DENIED);
  ASSERT_TRUE(trainee->Read(&frame));  // still driving

  // A tool the scene lacks: NOT_FOUND, and the trainee drives on.
  auto missing_context = As("admin-token");
  auto missing = open(true, missing_context.get(), "scalpel");
  while (missing->Read(&frame)) {
  }
  EXPECT_EQ(missing->Finish().error_code(), grpc::StatusCode::NOT_FOUND);
  ASSERT_TRUE(trainee->Read(&frame));

  auto instructor_context = As("admin-token");
  auto instructor = open(true, instructor_context.get());
  while (trainee->Read(&frame)) {
  }
  const grpc::Status ended = trainee->Finish();
  EXPECT_EQ(ended.error_code(), grpc::StatusCode::ABORTED);
  EXPECT_NE(ended.error_message().find("taken over by instructor"), std::string::npos)
      << ended.error_message();
  for (int n = 0; n < 100 && instructor->Read(&frame) && frame.tools(0).holder() != "instructor";
       ++n) {
  }
  EXPECT_EQ(frame.tools(0).holder(), "instructor");

  instructor->WritesDone();
  while (instructor->Read(&frame)) {
  }
  EXPECT_TRUE(instructor->Finish().ok());
  bool back = false;
  for (int attempt = 0; attempt < 200 && !back; ++attempt) {
    auto again_context = As("drive-token");
    auto again = open(false, again_context.get());
    back = again->Read(&frame);
    again_context->TryCancel();
    again->Finish();
    if (!back) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  EXPECT_TRUE(back);
}

// Reload takes a changed file at once; a broken file leaves the tokens
// read before in force.
TEST_F(AccessPolicyTest, ReloadSwapsTokensAndKeepsThemOnError) {
  WriteTokens({{"admin-token", "admin *"}, {"new-token", "watch *"}});
  absl::StatusOr<size_t> count = server_->access().Reload();
  ASSERT_TRUE(count.ok()) << count.status();
  EXPECT_EQ(*count, 2u);
  pb::ListScenesResponse listed;
  EXPECT_TRUE(scenes_->ListScenes(As("new-token").get(), {}, &listed).ok());
  EXPECT_EQ(scenes_->ListScenes(As("watch-token").get(), {}, &listed).error_code(),
            grpc::StatusCode::UNAUTHENTICATED);

  std::ofstream(tokens_file_) << "garbage\n";
  EXPECT_FALSE(server_->access().Reload().ok());
  EXPECT_TRUE(scenes_->ListScenes(As("new-token").get(), {}, &listed).ok());
}

// An open server lets any caller do anything, naming it by its address.
TEST(OpenAccessPolicyTest, OpenServerAllowsEverything) {
  TestServer server;
  server.Create(SmallScene("anything"));
  EXPECT_EQ(server.Get("anything").spec().name(), "anything");
}

}  // namespace
}  // namespace hs::testing

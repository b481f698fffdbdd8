#include "tests/server/test_server.h"

#include <gtest/gtest.h>

#include <chrono>

namespace hs::testing {

pb::Pose PoseAt(double x, double y, double z) {
  pb::Pose pose;
  pose.mutable_position_m()->set_x(x);
  pose.mutable_position_m()->set_y(y);
  pose.mutable_position_m()->set_z(z);
  return pose;
}

pb::SceneSpec SmallScene(const std::string& name, bool second_tool) {
  pb::SceneSpec spec;
  spec.set_name(name);
  spec.set_step_s(0.001);
  pb::SceneObject* table = spec.add_objects();
  table->set_name("table");
  table->set_kind(pb::OBJECT_KIND_FIXED);
  pb::Vector3* size = table->mutable_model()->mutable_procedural()->mutable_box()->mutable_size_m();
  size->set_x(0.2);
  size->set_y(0.2);
  size->set_z(0.02);
  auto add_tool = [&](const std::string& tool_name, double x) {
    pb::SceneObject* tool = spec.add_objects();
    tool->set_name(tool_name);
    tool->set_kind(pb::OBJECT_KIND_TOOL);
    pb::Vector3* s = tool->mutable_model()->mutable_procedural()->mutable_box()->mutable_size_m();
    s->set_x(0.02);
    s->set_y(0.02);
    s->set_z(0.02);
    *tool->mutable_pose() = PoseAt(x, 0, 0.05);
  };
  add_tool("probe", 0);
  if (second_tool) add_tool("stylus", 0.05);
  return spec;
}

TestServer::TestServer(const ServerLimits& limits, const RecordingOptions& recording) {
  ServerOptions options;
  options.listen = "127.0.0.1:0";
  options.limits = limits;
  options.recording = recording;
  absl::StatusOr<std::unique_ptr<HapticServer>> server = HapticServer::Start(options, metrics_);
  EXPECT_TRUE(server.ok()) << server.status();
  server_ = std::move(server).value();
  channel_ = grpc::CreateChannel(address(), grpc::InsecureChannelCredentials());
  scenes_ = pb::SceneService::NewStub(channel_);
  sessions_ = pb::SessionService::NewStub(channel_);
}

TestServer::~TestServer() { server_->Shutdown(0.5); }

std::string TestServer::address() const { return "127.0.0.1:" + std::to_string(server_->port()); }

void TestServer::Create(const pb::SceneSpec& spec) {
  pb::CreateSceneRequest request;
  *request.mutable_spec() = spec;
  pb::SceneInfo info;
  const grpc::Status status = scenes_->CreateScene(ContextWithin(10).get(), request, &info);
  ASSERT_TRUE(status.ok()) << status.error_message();
}

pb::SceneInfo TestServer::Get(const std::string& scene) {
  pb::GetSceneRequest request;
  request.set_scene(scene);
  pb::SceneInfo info;
  const grpc::Status status = scenes_->GetScene(ContextWithin(10).get(), request, &info);
  EXPECT_TRUE(status.ok()) << status.error_message();
  return info;
}

grpc::Status UploadModel(pb::SceneService::Stub& stub, const std::string& name,
                         const std::string& format, const std::string& data,
                         const std::string& sha256, size_t chunk_bytes,
                         pb::UploadModelResponse* response) {
  auto context = ContextWithin(30);
  auto writer = stub.UploadModel(context.get(), response);
  for (size_t offset = 0; offset == 0 || offset < data.size(); offset += chunk_bytes) {
    pb::UploadModelChunk chunk;
    if (offset == 0) {
      chunk.mutable_header()->set_name(name);
      chunk.mutable_header()->set_format(format);
      chunk.mutable_header()->set_size_bytes(static_cast<int64_t>(data.size()));
      chunk.mutable_header()->set_sha256(sha256);
    }
    chunk.set_data(data.substr(offset, chunk_bytes));
    if (!writer->Write(chunk)) break;
  }
  writer->WritesDone();
  return writer->Finish();
}

std::unique_ptr<DeviceStream> OpenDevice(pb::SessionService::Stub& stub,
                                         grpc::ClientContext& context, const std::string& scene,
                                         const std::string& tool) {
  std::unique_ptr<DeviceStream> stream = stub.Interact(&context);
  pb::InteractRequest open;
  open.mutable_open()->set_scene(scene);
  open.mutable_open()->set_tool(tool);
  if (!stream->Write(open)) {
    ADD_FAILURE() << "cannot ask for " << tool << " of " << scene;
    return nullptr;
  }
  return stream;
}

std::unique_ptr<grpc::ClientContext> ContextWithin(double seconds) {
  auto context = std::make_unique<grpc::ClientContext>();
  context->set_deadline(std::chrono::system_clock::now() +
                        std::chrono::milliseconds(static_cast<int64_t>(seconds * 1000)));
  return context;
}

}  // namespace hs::testing

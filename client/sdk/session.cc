#include "haptics/session.h"

#include <algorithm>
#include <chrono>
#include <fstream>
#include <sstream>

#include "absl/strings/str_cat.h"
#include "client/channel.h"
#include "client/health_check.h"
#include "client/model_upload.h"
#include "client/sdk/device_impl.h"
#include "client/sdk/grpc_error.h"
#include "client/sdk/session_impl.h"
#include "client/sdk/watcher_impl.h"
#include "client/server_call.h"
#include "common/api/proto_file.h"
#include "haptics/v1/scene_service.grpc.pb.h"

namespace haptics {
namespace {

namespace pb = haptics::v1;

// One SceneService request within the session's deadline.
template <typename Request, typename Response>
grpc::Status Call(const Session::Impl& impl,
                  grpc::Status (pb::SceneService::Stub::*method)(grpc::ClientContext*,
                                                                 const Request&, Response*),
                  const Request& request, Response* response) {
  auto stub = pb::SceneService::NewStub(impl.channel);
  auto context = hs::cli::ContextWithin(impl.options.call_timeout_s);
  return ((*stub).*method)(context.get(), request, response);
}

SceneInfo FromProto(const pb::SceneInfo& info) {
  return {.name = info.spec().name(),
          .step = info.step(),
          .step_s = info.step_s(),
          .triangles = info.triangles(),
          .devices = info.devices(),
          .viewers = info.viewers(),
          .revision = info.revision()};
}

Result<std::string> ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error{Code::kNotFound, "cannot read " + path};
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

}  // namespace

Session::Session(std::shared_ptr<Impl> impl) : impl_(std::move(impl)) {}
Session::~Session() = default;

Result<std::unique_ptr<Session>> Session::Connect(const std::string& address,
                                                  const SessionOptions& options) {
  hs::cli::ConnectionOptions connection;
  connection.address = address;
  connection.tls_ca_file = options.tls.ca_file;
  connection.tls_cert_file = options.tls.cert_file;
  connection.tls_key_file = options.tls.key_file;
  connection.tls_server_name = options.tls.server_name;
  connection.token = options.token;
  connection.token_file = options.token_file;
  // A device reconnects by itself (DeviceOptions' back-off): the channel
  // must not wait longer than that to try the server again.
  grpc::ChannelArguments arguments;
  arguments.SetInt(GRPC_ARG_INITIAL_RECONNECT_BACKOFF_MS, 100);
  arguments.SetInt(GRPC_ARG_MIN_RECONNECT_BACKOFF_MS, 100);
  arguments.SetInt(GRPC_ARG_MAX_RECONNECT_BACKOFF_MS, 1000);
  absl::StatusOr<std::shared_ptr<grpc::Channel>> channel =
      hs::cli::MakeChannel(connection, arguments);
  if (!channel.ok()) return hs::sdk::FromAbsl(channel.status());
  if (!(*channel)->WaitForConnected(
          std::chrono::system_clock::now() +
          std::chrono::microseconds(static_cast<int64_t>(options.connect_timeout_s * 1e6)))) {
    return Error{Code::kUnavailable, absl::StrCat("no server answered at ", address, " within ",
                                                  options.connect_timeout_s, " s")};
  }
  auto impl = std::make_shared<Impl>();
  impl->address = address;
  impl->options = options;
  impl->channel = *std::move(channel);
  return std::make_unique<Session>(std::move(impl));
}

Result<std::string> Session::Health(const std::string& service) {
  int serving = 0;
  const grpc::Status status =
      hs::cli::CheckHealth(impl_->channel, service, impl_->options.call_timeout_s, &serving);
  if (!status.ok()) return hs::sdk::FromGrpc(status);
  return std::string(hs::cli::ServingStatusName(serving));
}

Result<std::vector<SceneInfo>> Session::ListScenes() {
  pb::ListScenesResponse response;
  const grpc::Status status =
      Call(*impl_, &pb::SceneService::Stub::ListScenes, pb::ListScenesRequest(), &response);
  if (!status.ok()) return hs::sdk::FromGrpc(status);
  std::vector<SceneInfo> scenes;
  for (const pb::SceneInfo& info : response.scenes()) scenes.push_back(FromProto(info));
  return scenes;
}

Result<SceneInfo> Session::CreateScene(const std::string& spec_file, const std::string& name) {
  pb::CreateSceneRequest request;
  if (absl::Status read = hs::ReadProtoFile(spec_file, *request.mutable_spec()); !read.ok()) {
    return hs::sdk::FromAbsl(read);
  }
  if (!name.empty()) request.mutable_spec()->set_name(name);
  pb::SceneInfo response;
  const grpc::Status status =
      Call(*impl_, &pb::SceneService::Stub::CreateScene, request, &response);
  if (!status.ok()) return hs::sdk::FromGrpc(status);
  return FromProto(response);
}

Result<SceneInfo> Session::ReplaceScene(const std::string& spec_file, const std::string& name) {
  pb::SceneSpec spec;
  if (absl::Status read = hs::ReadProtoFile(spec_file, spec); !read.ok()) {
    return hs::sdk::FromAbsl(read);
  }
  const Error deleted = DeleteScene(name.empty() ? spec.name() : name);
  if (!deleted.ok() && deleted.code != Code::kNotFound) return deleted;
  return CreateScene(spec_file, name);
}

Error Session::DeleteScene(const std::string& name) {
  pb::DeleteSceneRequest request;
  request.set_scene(name);
  pb::DeleteSceneResponse response;
  return hs::sdk::FromGrpc(Call(*impl_, &pb::SceneService::Stub::DeleteScene, request, &response));
}

Result<ModelInfo> Session::UploadModel(const std::string& file, const std::string& name) {
  Result<std::string> bytes = ReadBytes(file);
  if (!bytes.ok()) return bytes.error();
  auto stub = pb::SceneService::NewStub(impl_->channel);
  pb::UploadModelResponse response;
  const grpc::Status status = hs::cli::UploadModelBytes(
      *stub, *bytes, name.empty() ? hs::cli::DefaultModelName(file) : name,
      hs::cli::ModelFormat(file), 1 << 20, impl_->options.call_timeout_s, &response);
  if (!status.ok()) return hs::sdk::FromGrpc(status);
  return ModelInfo{response.model_id(), response.vertices(), response.triangles()};
}

Error Session::DeleteModel(const std::string& model_id) {
  pb::DeleteModelRequest request;
  request.set_model_id(model_id);
  pb::DeleteModelResponse response;
  return hs::sdk::FromGrpc(Call(*impl_, &pb::SceneService::Stub::DeleteModel, request, &response));
}

Result<std::unique_ptr<Device>> Session::OpenDevice(const std::string& scene,
                                                    const std::string& tool,
                                                    const DeviceOptions& options) {
  if (!(options.rate_hz >= 1 && options.rate_hz <= 10000) ||
      !(options.frame_rate_hz == 0 ||
        (options.frame_rate_hz >= 1 && options.frame_rate_hz <= 10000)) ||
      !(options.tick_s > 0 && options.tick_s <= 1) ||
      !(options.max_passivity_damping_ns_per_m >= 0 &&
        options.max_passivity_damping_ns_per_m <= 1000) ||
      !(options.reconnect_initial_s > 0 &&
        options.reconnect_max_s >= options.reconnect_initial_s)) {
    return Error{Code::kInvalidArgument,
                 "rate_hz must be in [1, 10000], frame_rate_hz 0 or in [1, 10000], tick_s in "
                 "(0, 1], max_passivity_damping_ns_per_m in [0, 1000], and 0 < "
                 "reconnect_initial_s <= reconnect_max_s"};
  }
  // The scene's own rate bounds the frames a device may ask for.
  pb::GetSceneRequest request;
  request.set_scene(scene);
  pb::SceneInfo info;
  if (grpc::Status status = Call(*impl_, &pb::SceneService::Stub::GetScene, request, &info);
      !status.ok()) {
    return hs::sdk::FromGrpc(status);
  }
  hs::sdk::DeviceConfig config{.scene = scene, .tool = tool, .options = options};
  if (info.step_s() > 0) {
    const double frame_rate_hz =
        options.frame_rate_hz > 0 ? options.frame_rate_hz : options.rate_hz;
    config.options.rate_hz = std::min(options.rate_hz, 1 / info.step_s());
    config.options.frame_rate_hz = std::min(frame_rate_hz, 1 / info.step_s());
  }
  config.open_timeout_s =
      options.open_timeout_s > 0 ? options.open_timeout_s : impl_->options.connect_timeout_s;
  return hs::sdk::OpenDevice(impl_->channel, std::move(config));
}

Result<std::unique_ptr<Watcher>> Session::Watch(const std::string& scene, WatchOptions options) {
  if (options.open_timeout_s <= 0) options.open_timeout_s = impl_->options.connect_timeout_s;
  return hs::sdk::OpenWatcher(impl_->channel, scene, std::move(options));
}

}  // namespace haptics

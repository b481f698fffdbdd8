#include "server/haptic_server.h"

#include <grpcpp/ext/proto_server_reflection_plugin.h>
#include <grpcpp/health_check_service_interface.h>
#include <grpcpp/server_builder.h>

#include <chrono>
#include <filesystem>

#include "absl/strings/str_cat.h"
#include "common/core/status_macros.h"
#include "common/net/address.h"
#include "server/recording/recording_folder.h"
#include "server/thread_priority.h"

namespace hs {

absl::StatusOr<std::unique_ptr<HapticServer>> HapticServer::Start(const ServerOptions& options,
                                                                  Metrics& metrics) {
  if (options.limits.realtime_priority != 0) {
    HS_RETURN_IF_ERROR(CheckRealtimePriority(options.limits.realtime_priority));
  }
  if (!options.tls.enabled() && !options.insecure_listen && !IsLoopbackAddress(options.listen)) {
    return absl::FailedPreconditionError(
        absl::StrCat(options.listen,
                     " is reachable from other machines: serve it with TLS (--tls-cert, "
                     "--tls-key), or give --insecure-listen to serve it in the clear"));
  }
  absl::StatusOr<std::shared_ptr<grpc::ServerCredentials>> credentials =
      MakeServerCredentials(options.tls);
  if (!credentials.ok()) return credentials.status();
  std::unique_ptr<HapticServer> server(new HapticServer());
  if (options.tokens_file.empty()) {
    server->access_ = std::make_unique<AccessPolicy>();
  } else {
    absl::StatusOr<std::unique_ptr<AccessPolicy>> access =
        AccessPolicy::FromFile(options.tokens_file);
    if (!access.ok()) return access.status();
    server->access_ = *std::move(access);
  }
  std::string model_dir = options.model_dir;
  std::unique_ptr<SceneCatalogue> catalogue;
  if (!options.state_dir.empty()) {
    std::error_code error;
    std::filesystem::create_directories(options.state_dir, error);
    if (error) {
      return absl::UnavailableError(
          absl::StrCat("cannot make the state folder ", options.state_dir, ": ", error.message()));
    }
    if (model_dir.empty())
      model_dir = (std::filesystem::path(options.state_dir) / "models").string();
    absl::StatusOr<std::unique_ptr<SceneCatalogue>> opened =
        SceneCatalogue::Open((std::filesystem::path(options.state_dir) / "scenes.db").string());
    if (!opened.ok()) return opened.status();
    catalogue = *std::move(opened);
  }
  if (model_dir.empty()) {
    absl::StatusOr<TemporaryModelDir> made = TemporaryModelDir::Make();
    if (!made.ok()) return made.status();
    model_dir = made->path();
    server->temporary_model_dir_ = *std::move(made);
  }
  if (!options.recording.dir.empty()) {
    if (absl::Status s = PrepareRecordingFolder(options.recording.dir); !s.ok()) return s;
  }
  server->registry_ = std::make_unique<SceneRegistry>(options.limits, model_dir, metrics,
                                                      std::move(catalogue), options.recording);
  // Before the port opens: no client sees the server without its scenes.
  if (absl::Status s = server->registry_->RestoreScenes(); !s.ok()) return s;
  server->scene_service_ = std::make_unique<SceneServiceImpl>(*server->registry_, *server->access_);
  server->session_service_ =
      std::make_unique<SessionServiceImpl>(*server->registry_, *server->access_);

  grpc::EnableDefaultHealthCheckService(true);
  grpc::reflection::InitProtoReflectionServerBuilderPlugin();
  grpc::ServerBuilder builder;
  builder.AddListeningPort(options.listen, *credentials, &server->port_);
  builder.RegisterService(server->scene_service_.get());
  builder.RegisterService(server->session_service_.get());
  builder.SetMaxReceiveMessageSize(options.max_receive_bytes);
  builder.SetMaxSendMessageSize(64 << 20);
  // Long streams: ping idle connections every 20 s, drop them when a ping
  // goes unanswered for 10 s; let clients ping every 10 s even when idle.
  builder.AddChannelArgument(GRPC_ARG_KEEPALIVE_TIME_MS, 20000);
  builder.AddChannelArgument(GRPC_ARG_KEEPALIVE_TIMEOUT_MS, 10000);
  builder.AddChannelArgument(GRPC_ARG_KEEPALIVE_PERMIT_WITHOUT_CALLS, 1);
  builder.AddChannelArgument(GRPC_ARG_HTTP2_MIN_RECV_PING_INTERVAL_WITHOUT_DATA_MS, 10000);
  builder.AddChannelArgument(GRPC_ARG_HTTP2_MAX_PINGS_WITHOUT_DATA, 0);
  server->server_ = builder.BuildAndStart();
  if (server->server_ == nullptr || server->port_ == 0) {
    return absl::UnavailableError(absl::StrCat("cannot listen on ", options.listen));
  }
  server->server_->GetHealthCheckService()->SetServingStatus(true);
  return server;
}

HapticServer::~HapticServer() { Shutdown(); }

void HapticServer::Drain() {
  if (drained_ || server_ == nullptr) return;
  drained_ = true;
  server_->GetHealthCheckService()->SetServingStatus(false);
  registry_->StopAll(absl::UnavailableError("the server is shutting down"));
}

void HapticServer::Shutdown(double grace_s) {
  if (shut_down_ || server_ == nullptr) return;
  shut_down_ = true;
  Drain();
  server_->Shutdown(std::chrono::system_clock::now() +
                    std::chrono::milliseconds(static_cast<int64_t>(grace_s * 1000)));
  server_->Wait();
}

}  // namespace hs

#pragma once
// The whole server: the gRPC services, health checking, reflection, the
// scene registry and metrics, with the channel settings for long streams.

#include <grpcpp/server.h>

#include <memory>
#include <optional>
#include <string>

#include "absl/status/statusor.h"
#include "server/auth/access_policy.h"
#include "server/auth/tls_credentials.h"
#include "server/metrics.h"
#include "server/scene_registry.h"
#include "server/scene_service.h"
#include "server/session_service.h"
#include "server/temporary_model_dir.h"

namespace hs {

struct ServerOptions {
  /// host:port to listen on; port 0 picks a free one (see port()).
  std::string listen = "127.0.0.1:50051";
  /// TLS certificate and key (and client CA for mutual TLS); empty: none.
  ServerTlsFiles tls;
  /// Lets `listen` name an address other machines reach without TLS.
  bool insecure_listen = false;
  /// Tokens and roles (token_table.h); empty: an open server, where any
  /// caller may do anything.
  std::string tokens_file;
  ServerLimits limits;
  /// Folder for uploaded models; empty: state_dir/models with a state
  /// folder, else a fresh temporary folder, removed when the server is
  /// destroyed.
  std::string model_dir;
  /// Folder of the state kept across restarts (scenes.db, the scene
  /// catalogue, and models/); empty: scenes live in memory only.
  std::string state_dir;
  /// Session recording (--record-dir and its flags); off without a dir.
  RecordingOptions recording;
  /// Largest message received, bytes (model chunks, scene specs).
  int max_receive_bytes = 16 << 20;
};

class HapticServer {
 public:
  /// Starts serving. UNAVAILABLE when it cannot listen on options.listen;
  /// INVALID_ARGUMENT for unusable TLS files (MakeServerCredentials) or
  /// tokens file (TokenTable::Read);
  /// FAILED_PRECONDITION when options.listen is reachable from other
  /// machines without TLS and insecure_listen is not set, or when the
  /// state folder's catalogue is foreign or damaged or one of its scenes
  /// does not start (SceneRegistry::RestoreScenes): never on half a state.
  /// `metrics` outlives the server.
  static absl::StatusOr<std::unique_ptr<HapticServer>> Start(const ServerOptions& options,
                                                             Metrics& metrics);
  /// Shutdown() if not done yet; removes a temporary model folder.
  ~HapticServer();

  /// The port it listens on.
  int port() const { return port_; }
  SceneRegistry& registry() { return *registry_; }
  /// Who may call what; Reload() it when the tokens file changes.
  AccessPolicy& access() { return *access_; }

  /// First half of a graceful stop: health goes NOT_SERVING and every
  /// scene runs a final step and ends its streams with UNAVAILABLE; the
  /// port stays open (health checks see NOT_SERVING) until Shutdown.
  /// Later calls do nothing.
  void Drain();
  /// Graceful stop: Drain, then calls in flight get up to `grace_s`
  /// seconds before they are cancelled. Later calls do nothing.
  void Shutdown(double grace_s = 2.0);

 private:
  HapticServer() = default;

  int port_ = 0;
  std::optional<TemporaryModelDir> temporary_model_dir_;  // outlives registry_
  std::unique_ptr<AccessPolicy> access_;
  std::unique_ptr<SceneRegistry> registry_;
  std::unique_ptr<SceneServiceImpl> scene_service_;
  std::unique_ptr<SessionServiceImpl> session_service_;
  std::unique_ptr<grpc::Server> server_;
  bool drained_ = false;
  bool shut_down_ = false;
};

}  // namespace hs

#pragma once
// An in-process haptics.v1.EchoService on a free 127.0.0.1 port: the bare
// gRPC baseline of `hapticctl loadtest`. Callback API, one reactor per
// stream, like haptic-server's sessions.

#include <grpcpp/server.h>

#include <memory>

#include "absl/status/statusor.h"

namespace hs::cli {

class EchoBaselineServer {
 public:
  /// Starts serving on 127.0.0.1 at a free port. UNAVAILABLE when it
  /// cannot listen.
  static absl::StatusOr<std::unique_ptr<EchoBaselineServer>> Start();
  /// Shuts down (streams still open are cancelled).
  ~EchoBaselineServer();

  /// "127.0.0.1:PORT".
  std::string address() const;

 private:
  EchoBaselineServer() = default;
  int port_ = 0;
  std::unique_ptr<grpc::Service> service_;
  std::unique_ptr<grpc::Server> server_;
};

}  // namespace hs::cli

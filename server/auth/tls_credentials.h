#pragma once
// The transport security haptic-server offers: plain TCP or TLS, with or
// without client certificates (mutual TLS).

#include <grpcpp/security/server_credentials.h>

#include <memory>
#include <string>

#include "absl/status/statusor.h"

namespace hs {

/// PEM files for TLS; all empty: no TLS.
struct ServerTlsFiles {
  /// The server's certificate chain.
  std::string cert_file;
  /// The certificate's private key.
  std::string key_file;
  /// CAs that sign client certificates; set: every client must present
  /// one they signed (mutual TLS).
  std::string client_ca_file;

  bool enabled() const { return !cert_file.empty() || !key_file.empty(); }
};

/// Insecure credentials when `files` is empty, TLS otherwise.
/// INVALID_ARGUMENT naming the file when a file cannot be read or holds no
/// PEM certificate or key, when only one of cert and key is given, when a
/// client CA comes without them, or when the key is not the certificate's.
absl::StatusOr<std::shared_ptr<grpc::ServerCredentials>> MakeServerCredentials(
    const ServerTlsFiles& files);

}  // namespace hs

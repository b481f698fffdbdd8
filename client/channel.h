#pragma once
// The channel every hapticctl command opens to haptic-server: plain or
// TLS (with a client certificate for mutual TLS), and the bearer token
// sent with every call on it.

#include <grpcpp/grpcpp.h>

#include <memory>

#include "absl/status/statusor.h"
#include "client/server_call.h"

namespace hs::cli {

/// A channel to options.address: TLS when options.tls_ca_file is set
/// (presenting options.tls_cert_file and tls_key_file when set); every
/// call on it carries "authorization: Bearer TOKEN" when a token is given
/// (options.token, else options.token_file, else the HAPTIC_TOKEN
/// environment variable).
/// INVALID_ARGUMENT naming the file when a file cannot be read, a token
/// is empty, or only one of cert and key is given.
absl::StatusOr<std::shared_ptr<grpc::Channel>> MakeChannel(const ConnectionOptions& options);
/// As above, with `arguments` (reconnection back-off, ...) on the channel.
absl::StatusOr<std::shared_ptr<grpc::Channel>> MakeChannel(const ConnectionOptions& options,
                                                           grpc::ChannelArguments arguments);

}  // namespace hs::cli

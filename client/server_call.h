#pragma once
// What every hapticctl command that talks to haptic-server shares: the
// connection options (the channel itself: channel.h), deadlines, and turning a
// gRPC status into a message on stderr and an exit status (exit_codes.h).

#include <google/protobuf/message.h>
#include <grpcpp/grpcpp.h>

#include <memory>
#include <ostream>
#include <string>
#include <string_view>

#include "CLI/CLI.hpp"
#include "absl/status/status.h"

namespace hs::cli {

/// Where the server is and how long a unary call may take.
struct ConnectionOptions {
  /// host:port of haptic-server.
  std::string address = "127.0.0.1:50051";
  /// Deadline of each unary call, seconds.
  double timeout_s = 10;
  /// PEM CA certificates that sign the server's certificate; set: TLS.
  std::string tls_ca_file;
  /// PEM client certificate and key, for a server that requires one.
  std::string tls_cert_file;
  std::string tls_key_file;
  /// The name the server's certificate must carry, when not the address's host.
  std::string tls_server_name;
  /// File holding the bearer token; empty: HAPTIC_TOKEN, if set.
  std::string token_file;
  /// The bearer token itself, before token_file (the client SDK's callers
  /// hand it over).
  std::string token;
};

/// Adds --server, --timeout, the TLS options and --token-file to `cmd`,
/// filling `options`.
void AddConnectionOptions(CLI::App& cmd, ConnectionOptions& options);

/// A client context whose call gives up after `seconds`.
std::unique_ptr<grpc::ClientContext> ContextWithin(double seconds);

/// "NOT_FOUND", "UNAVAILABLE", ...: the canonical name of `code`.
std::string StatusCodeName(grpc::StatusCode code);

/// The exit status for a call that ended with `status`: kExitOk;
/// kExitUnavailable for UNAVAILABLE and DEADLINE_EXCEEDED; kExitNotFound
/// for NOT_FOUND; kExitRefused for a request the server turned down
/// (INVALID_ARGUMENT, ALREADY_EXISTS, FAILED_PRECONDITION,
/// RESOURCE_EXHAUSTED, PERMISSION_DENIED, UNAUTHENTICATED, OUT_OF_RANGE,
/// UNIMPLEMENTED); kExitFailure for anything else.
int ExitCodeFor(const grpc::Status& status);

/// Prints "hapticctl COMMAND: CODE: message" to `err` and returns
/// ExitCodeFor(status). For statuses that are not OK.
int ReportRpcError(std::string_view command, const grpc::Status& status, std::ostream& err);

/// Prints "hapticctl COMMAND: message" to `err` for a local failure (a
/// file, a value) and returns kExitFailure.
int ReportError(std::string_view command, std::string_view message, std::ostream& err);
/// As above with a status's message.
int ReportError(std::string_view command, const absl::Status& status, std::ostream& err);

/// `message` as one line of JSON with the proto field names.
std::string ProtoToJsonLine(const google::protobuf::Message& message);

}  // namespace hs::cli

#include "client/server_call.h"

#include <google/protobuf/util/json_util.h>

#include <chrono>

#include "absl/strings/str_cat.h"
#include "client/exit_codes.h"

namespace hs::cli {

void AddConnectionOptions(CLI::App& cmd, ConnectionOptions& options) {
  cmd.add_option("--server", options.address, "haptic-server address, host:port")
      ->capture_default_str();
  cmd.add_option("--timeout", options.timeout_s, "Deadline of each request, seconds")
      ->check(CLI::Range(0.01, 3600.0))
      ->capture_default_str();
  cmd.add_option("--tls-ca", options.tls_ca_file,
                 "PEM CA certificates that sign the server's: connect over TLS")
      ->check(CLI::ExistingFile);
  cmd.add_option("--tls-cert", options.tls_cert_file,
                 "PEM client certificate, for servers that require one (with --tls-key)")
      ->check(CLI::ExistingFile);
  cmd.add_option("--tls-key", options.tls_key_file, "PEM private key of --tls-cert")
      ->check(CLI::ExistingFile);
  cmd.add_option("--tls-server-name", options.tls_server_name,
                 "Name the server's certificate carries, when not --server's host");
  cmd.add_option("--token-file", options.token_file,
                 "File holding the bearer token (default: the HAPTIC_TOKEN variable)")
      ->check(CLI::ExistingFile);
}

std::unique_ptr<grpc::ClientContext> ContextWithin(double seconds) {
  auto context = std::make_unique<grpc::ClientContext>();
  context->set_deadline(std::chrono::system_clock::now() +
                        std::chrono::microseconds(static_cast<int64_t>(seconds * 1e6)));
  return context;
}

std::string StatusCodeName(grpc::StatusCode code) {
  // gRPC and Abseil share their status codes and names.
  return absl::StatusCodeToString(static_cast<absl::StatusCode>(code));
}

int ExitCodeFor(const grpc::Status& status) {
  switch (status.error_code()) {
    case grpc::StatusCode::OK:
      return kExitOk;
    case grpc::StatusCode::UNAVAILABLE:
    case grpc::StatusCode::DEADLINE_EXCEEDED:
      return kExitUnavailable;
    case grpc::StatusCode::NOT_FOUND:
      return kExitNotFound;
    case grpc::StatusCode::INVALID_ARGUMENT:
    case grpc::StatusCode::ALREADY_EXISTS:
    case grpc::StatusCode::FAILED_PRECONDITION:
    case grpc::StatusCode::RESOURCE_EXHAUSTED:
    case grpc::StatusCode::PERMISSION_DENIED:
    case grpc::StatusCode::UNAUTHENTICATED:
    case grpc::StatusCode::OUT_OF_RANGE:
    case grpc::StatusCode::UNIMPLEMENTED:
      return kExitRefused;
    default:
      return kExitFailure;
  }
}

int ReportRpcError(std::string_view command, const grpc::Status& status, std::ostream& err) {
  err << "hapticctl " << command << ": " << StatusCodeName(status.error_code()) << ": "
      << status.error_message() << "\n";
  return ExitCodeFor(status);
}

int ReportError(std::string_view command, std::string_view message, std::ostream& err) {
  err << "hapticctl " << command << ": " << message << "\n";
  return kExitFailure;
}

int ReportError(std::string_view command, const absl::Status& status, std::ostream& err) {
  return ReportError(command, std::string_view(status.message().data(), status.message().size()),
                     err);
}

std::string ProtoToJsonLine(const google::protobuf::Message& message) {
  std::string text;
  google::protobuf::util::JsonPrintOptions options;
  options.preserve_proto_field_names = true;
  (void)google::protobuf::util::MessageToJsonString(message, &text, options);
  return text;
}

}  // namespace hs::cli

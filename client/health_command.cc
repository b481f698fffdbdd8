#include "client/health_command.h"

#include <google/protobuf/wrappers.pb.h>
#include <grpcpp/generic/generic_stub.h>
#include <grpcpp/impl/codegen/proto_utils.h>

#include <future>
#include <iostream>

#include "client/channel.h"
#include "client/exit_codes.h"

namespace hs::cli {
namespace {

// grpc.health.v1 ships no C++ client with gRPC. Its two messages have the
// wire form of the protobuf wrappers: HealthCheckRequest is field 1 string
// `service` (StringValue), HealthCheckResponse field 1 enum `status`
// (Int32Value).
using HealthRequest = google::protobuf::StringValue;
using HealthResponse = google::protobuf::Int32Value;

const char* ServingStatusName(int status) {
  switch (status) {
    case 1:
      return "SERVING";
    case 2:
      return "NOT_SERVING";
    case 3:
      return "SERVICE_UNKNOWN";
    default:
      return "UNKNOWN";
  }
}

}  // namespace

int RunHealth(const HealthArgs& args, std::ostream& out, std::ostream& err) {
  absl::StatusOr<std::shared_ptr<grpc::Channel>> channel = MakeChannel(args.server);
  if (!channel.ok()) return ReportError("health", channel.status(), err);
  grpc::TemplatedGenericStub<HealthRequest, HealthResponse> stub(*channel);
  auto context = ContextWithin(args.server.timeout_s);
  HealthRequest request;
  request.set_value(args.service);
  HealthResponse response;
  std::promise<grpc::Status> done;
  stub.UnaryCall(context.get(), "/grpc.health.v1.Health/Check", grpc::StubOptions(), &request,
                 &response, [&done](grpc::Status status) { done.set_value(std::move(status)); });
  const grpc::Status status = done.get_future().get();
  if (!status.ok()) return ReportRpcError("health", status, err);
  out << ServingStatusName(response.value()) << "\n";
  return response.value() == 1 ? kExitOk : kExitNotServing;
}

void AddHealthCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<HealthArgs>();
  CLI::App* cmd = app.add_subcommand("health", "Is the server serving? (grpc.health.v1)");
  AddConnectionOptions(*cmd, args->server);
  cmd->add_option("--service", args->service,
                  "A service's full name, e.g. haptics.v1.SceneService (default: the server)");
  cmd->callback([args, &exit_code] { exit_code = RunHealth(*args, std::cout, std::cerr); });
}

}  // namespace hs::cli

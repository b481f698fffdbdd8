#include "client/health_check.h"

#include <google/protobuf/wrappers.pb.h>
#include <grpcpp/generic/generic_stub.h>
#include <grpcpp/impl/codegen/proto_utils.h>

#include <chrono>
#include <future>

namespace hs::cli {
namespace {

// grpc.health.v1 ships no C++ client with gRPC. Its two messages have the
// wire form of the protobuf wrappers: HealthCheckRequest is field 1 string
// `service` (StringValue), HealthCheckResponse field 1 enum `status`
// (Int32Value).
using HealthRequest = google::protobuf::StringValue;
using HealthResponse = google::protobuf::Int32Value;

}  // namespace

grpc::Status CheckHealth(const std::shared_ptr<grpc::Channel>& channel, const std::string& service,
                         double timeout_s, int* status) {
  grpc::TemplatedGenericStub<HealthRequest, HealthResponse> stub(channel);
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() +
                       std::chrono::microseconds(static_cast<int64_t>(timeout_s * 1e6)));
  HealthRequest request;
  request.set_value(service);
  HealthResponse response;
  std::promise<grpc::Status> done;
  stub.UnaryCall(&context, "/grpc.health.v1.Health/Check", grpc::StubOptions(), &request, &response,
                 [&done](grpc::Status s) { done.set_value(std::move(s)); });
  grpc::Status result = done.get_future().get();
  *status = response.value();
  return result;
}

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

}  // namespace hs::cli

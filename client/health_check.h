#pragma once
// grpc.health.v1 Health.Check on a channel. Shared by `hapticctl health`
// and the client SDK.

#include <grpcpp/grpcpp.h>

#include <memory>
#include <string>

namespace hs::cli {

/// SERVING is 1 (grpc.health.v1.HealthCheckResponse.ServingStatus).
inline constexpr int kServing = 1;

/// Asks whether `service` (empty: the server) is serving; fills `status`.
grpc::Status CheckHealth(const std::shared_ptr<grpc::Channel>& channel, const std::string& service,
                         double timeout_s, int* status);

/// "SERVING", "NOT_SERVING", "SERVICE_UNKNOWN" or "UNKNOWN".
const char* ServingStatusName(int status);

}  // namespace hs::cli

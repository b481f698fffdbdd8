#pragma once
// gRPC and Abseil statuses as the SDK's Error (haptics/error.h).

#include <grpcpp/grpcpp.h>

#include "absl/status/status.h"
#include "haptics/error.h"

namespace hs::sdk {

haptics::Error FromGrpc(const grpc::Status& status);
haptics::Error FromAbsl(const absl::Status& status);

}  // namespace hs::sdk

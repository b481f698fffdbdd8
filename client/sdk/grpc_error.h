#pragma once
// gRPC and Abseil statuses as the SDK's Error (haptics/error.h), and back
// to gRPC's.

#include <grpcpp/grpcpp.h>

#include "absl/status/status.h"
#include "haptics/error.h"

namespace hs::sdk {

haptics::Error FromGrpc(const grpc::Status& status);
haptics::Error FromAbsl(const absl::Status& status);
/// The other way, for the SDK's own programs (hapticctl) that report a
/// gRPC status.
grpc::Status ToGrpc(const haptics::Error& error);

}  // namespace hs::sdk

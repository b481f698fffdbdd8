#pragma once
// absl::Status -> grpc::Status at the RPC edge. The two share their codes.

#include <grpcpp/support/status.h>

#include <string>

#include "absl/status/status.h"

namespace hs {

/// The same code and message.
inline grpc::Status ToGrpcStatus(const absl::Status& status) {
  if (status.ok()) return grpc::Status::OK;
  return grpc::Status(static_cast<grpc::StatusCode>(status.code()), std::string(status.message()));
}

}  // namespace hs

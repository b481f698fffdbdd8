#include "client/sdk/grpc_error.h"

#include <string>

namespace hs::sdk {

haptics::Error FromGrpc(const grpc::Status& status) {
  return {static_cast<haptics::Code>(status.error_code()), status.error_message()};
}

haptics::Error FromAbsl(const absl::Status& status) {
  return {static_cast<haptics::Code>(status.code()), std::string(status.message())};
}

grpc::Status ToGrpc(const haptics::Error& error) {
  if (error.ok()) return grpc::Status::OK;
  return grpc::Status(static_cast<grpc::StatusCode>(error.code), error.message);
}

}  // namespace hs::sdk

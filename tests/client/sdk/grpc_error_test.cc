#include "client/sdk/grpc_error.h"

#include <gtest/gtest.h>

namespace hs::sdk {
namespace {

TEST(GrpcErrorTest, KeepsCodeAndMessage) {
  // A gRPC or Abseil status becomes the Error of the same code and message.
  const haptics::Error from_grpc =
      FromGrpc(grpc::Status(grpc::StatusCode::NOT_FOUND, "no scene 'x'"));
  EXPECT_EQ(from_grpc.ToString(), "NOT_FOUND: no scene 'x'");
  const haptics::Error from_absl = FromAbsl(absl::PermissionDeniedError("read only"));
  EXPECT_EQ(from_absl.ToString(), "PERMISSION_DENIED: read only");
  EXPECT_TRUE(FromGrpc(grpc::Status::OK).ok());
}

TEST(GrpcErrorTest, ToGrpcRoundTrips) {
  // ToGrpc gives back the status FromGrpc took, for every code.
  for (int code = 0; code <= 16; ++code) {
    const grpc::Status status(static_cast<grpc::StatusCode>(code), code == 0 ? "" : "why");
    const grpc::Status back = ToGrpc(FromGrpc(status));
    EXPECT_EQ(back.error_code(), status.error_code());
    EXPECT_EQ(back.error_message(), status.error_message());
  }
}

}  // namespace
}  // namespace hs::sdk

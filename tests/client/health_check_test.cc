#include "client/health_check.h"

#include <gtest/gtest.h>

#include "tests/server/test_server.h"

namespace hs::cli {
namespace {

TEST(HealthCheckTest, ARunningServerIsServing) {
  // The server's own status, and a service it does not have.
  testing::TestServer server;
  int status = 0;
  ASSERT_TRUE(CheckHealth(server.channel(), "", 10, &status).ok());
  EXPECT_EQ(status, kServing);
  EXPECT_STREQ(ServingStatusName(status), "SERVING");
  const grpc::Status unknown = CheckHealth(server.channel(), "no.such.Service", 10, &status);
  EXPECT_EQ(unknown.error_code(), grpc::StatusCode::NOT_FOUND);
}

TEST(HealthCheckTest, StatusNamesAreGrpcHealths) {
  // grpc.health.v1.HealthCheckResponse.ServingStatus, by number.
  EXPECT_STREQ(ServingStatusName(0), "UNKNOWN");
  EXPECT_STREQ(ServingStatusName(1), "SERVING");
  EXPECT_STREQ(ServingStatusName(2), "NOT_SERVING");
  EXPECT_STREQ(ServingStatusName(3), "SERVICE_UNKNOWN");
  EXPECT_STREQ(ServingStatusName(7), "UNKNOWN");
}

}  // namespace
}  // namespace hs::cli

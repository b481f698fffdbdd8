#include "client/health_command.h"

#include <gtest/gtest.h>

#include <sstream>

#include "client/exit_codes.h"
#include "tests/server/test_server.h"

namespace hs::cli {
namespace {

// A running server is SERVING (exit 0); an
// unknown service is NOT_FOUND and a server that is not there UNAVAILABLE.
TEST(HealthCommandTest, ServingUnknownAndUnreachable) {
  hs::testing::TestServer server;
  std::ostringstream out, err;
  HealthArgs args;
  args.server.address = server.address();
  ASSERT_EQ(RunHealth(args, out, err), kExitOk) << err.str();
  EXPECT_EQ(out.str(), "SERVING\n");
  args.service = "no.such.Service";
  EXPECT_EQ(RunHealth(args, out, err), kExitNotFound);
  args.service = "";
  args.server.address = "127.0.0.1:1";
  EXPECT_EQ(RunHealth(args, out, err), kExitUnavailable);
  EXPECT_NE(err.str().find("UNAVAILABLE: "), std::string::npos) << err.str();
}

}  // namespace
}  // namespace hs::cli

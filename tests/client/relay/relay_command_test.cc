#include "client/relay/relay_command.h"

#include <gtest/gtest.h>

#include <limits>
#include <sstream>

#include "client/exit_codes.h"

namespace hs::cli {
namespace {

// Values out of range, non-finite ones and addresses off loopback exit 2
// with a message naming what was wrong.
TEST(RelayCommandTest, BadArgumentsAreUsageErrors) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::string local = "127.0.0.1:9";
  for (const auto& [args, word] :
       {std::pair{RelayArgs{.relay = {.to = local, .stall_prob = 2}}, "stall probability"},
        std::pair{RelayArgs{.relay = {.to = local, .stall_ms = nan}}, "stall time"},
        std::pair{RelayArgs{.relay = {.to = local, .one_way_ms = -1}}, "one-way"},
        std::pair{RelayArgs{.relay = {.to = "192.168.1.1:80"}}, "--allow-remote"},
        std::pair{RelayArgs{.relay = {.listen = "0.0.0.0:0", .to = local}}, "--listen"},
        std::pair{RelayArgs{.relay = {.to = local}, .duration_s = nan}, "--duration-s"}}) {
    std::ostringstream out, err;
    EXPECT_EQ(RunRelay(args, out, err), kExitUsage) << word;
    EXPECT_NE(err.str().find(word), std::string::npos) << err.str();
    EXPECT_EQ(out.str(), "");
  }
}

// A relay given a duration says where it listens, runs to its end and
// reports its counters.
TEST(RelayCommandTest, RunsForItsDuration) {
  std::ostringstream out, err;
  EXPECT_EQ(
      RunRelay({.relay = {.to = "127.0.0.1:9", .one_way_ms = 20}, .duration_s = 0.05}, out, err),
      kExitOk)
      << err.str();
  EXPECT_NE(out.str().find("relay: listening on port "), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("0 connections"), std::string::npos) << out.str();
}

}  // namespace
}  // namespace hs::cli

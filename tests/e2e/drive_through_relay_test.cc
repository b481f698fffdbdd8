// A remote device over a real TCP link: the built haptic-server, the relay
// in front of it at 20 ms each way with jitter and head-of-line stalls,
// and `hapticctl drive --operator press` through the relay.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sstream>

#include "client/drive_command.h"
#include "client/exit_codes.h"
#include "client/relay/tcp_relay.h"
#include "tests/server/server_process.h"

namespace hs::cli {
namespace {

// The press runs to its end through the relay, and the round trip it
// measures (pose sent to the frame that applied it read) is at least the
// relay's 20 ms each way; the relay stalled some chunks on the way.
TEST(DriveThroughRelayTest, PressCompletesAndSeesTheRoundTrip) {
  hs::testing::ServerProcess server;
  ASSERT_NE(server.port(), 0) << server.startup();
  absl::StatusOr<std::unique_ptr<TcpRelay>> relay =
      TcpRelay::Start({.to = "127.0.0.1:" + std::to_string(server.port()),
                       .one_way_ms = 20,
                       .jitter_ms = 5,
                       .stall_prob = 0.02,
                       .stall_ms = 30,
                       .seed = 1});
  ASSERT_TRUE(relay.ok()) << relay.status();
  DriveArgs args;
  args.server.address = "127.0.0.1:" + std::to_string((*relay)->port());
  args.scene = "probe on torus";
  args.tool = "probe";
  args.operator_motion = "press";
  args.duration_s = 1.5;
  args.json = true;
  std::ostringstream out, err;
  ASSERT_EQ(RunDrive(args, out, err), kExitOk) << err.str();
  const nlohmann::json summary = nlohmann::json::parse(out.str());
  EXPECT_EQ(summary["ticks"], 1500);
  EXPECT_GE(summary["round_trip_p50_ms"].get<double>(), 40);
  EXPECT_GE(summary["round_trip_p99_ms"].get<double>(), summary["round_trip_p50_ms"].get<double>());
  (*relay)->Stop();
  const TcpRelay::Counters counters = (*relay)->counters();
  EXPECT_GE(counters.connections, 1);
  EXPECT_GT(counters.stalls, 0);
  EXPECT_GT(counters.bytes_down, 0);
}

}  // namespace
}  // namespace hs::cli

// A remote device over a real TCP link: the built haptic-server, the relay
// in front of it with jitter and head-of-line stalls, and `hapticctl drive
// --operator` through the relay.

#include <gtest/gtest.h>

#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "client/drive_command.h"
#include "client/exit_codes.h"
#include "client/relay/tcp_relay.h"
#include "tests/server/server_process.h"

namespace hs::cli {
namespace {

// `hapticctl drive --operator OP` for `duration_s` at `address` (the
// local model on), its JSON summary (discarded when the run failed).
nlohmann::json DriveOperator(const std::string& address, const std::string& op, double duration_s) {
  DriveArgs args;
  args.server.address = address;
  args.scene = "probe on torus";
  args.tool = "probe";
  args.operator_motion = op;
  args.duration_s = duration_s;
  args.json = true;
  std::ostringstream out, err;
  EXPECT_EQ(RunDrive(args, out, err), kExitOk) << err.str();
  return nlohmann::json::parse(out.str(), nullptr, false);
}

// The relay's link; the test fills in where it relays to.
class SlideThroughRelayTest : public ::testing::TestWithParam<RelayOptions> {};

// The slide across the organ's crest through the relay (links of the study
// in docs/remote-haptics.md: 50 ms each way, 10 ms jitter and 1 % of
// chunks held 100 ms; 150 ms each way and 20 ms jitter) stays passive (at
// most 1 mJ into the hand over 4 s), and the hand goes no deeper than
// twice what it does straight at the server, with no latency.
TEST_P(SlideThroughRelayTest, StaysPassiveAndShallow) {
  hs::testing::ServerProcess server;
  ASSERT_NE(server.port(), 0) << server.startup();
  const std::string direct = "127.0.0.1:" + std::to_string(server.port());
  RelayOptions link = GetParam();
  link.to = direct;
  absl::StatusOr<std::unique_ptr<TcpRelay>> relay = TcpRelay::Start(link);
  ASSERT_TRUE(relay.ok()) << relay.status();
  const nlohmann::json reference = DriveOperator(direct, "slide", 4);
  const nlohmann::json linked =
      DriveOperator("127.0.0.1:" + std::to_string((*relay)->port()), "slide", 4);
  ASSERT_TRUE(reference.is_object() && linked.is_object());
  std::cout << "reference: " << reference.dump() << "\nthrough the relay: " << linked.dump()
            << "\n";
  EXPECT_GE(linked["round_trip_p50_ms"].get<double>(), 2 * link.one_way_ms);
  EXPECT_GT(reference["penetration_p99_m"].get<double>(), 0) << "the hand must reach the organ";
  EXPECT_LE(linked["energy_j"].get<double>(), 1e-3);
  EXPECT_LE(linked["penetration_p99_m"].get<double>(),
            2 * reference["penetration_p99_m"].get<double>());
}

INSTANTIATE_TEST_SUITE_P(Links, SlideThroughRelayTest,
                         ::testing::Values(RelayOptions{.one_way_ms = 50,
                                                        .jitter_ms = 10,
                                                        .stall_prob = 0.01,
                                                        .stall_ms = 100},
                                           RelayOptions{.one_way_ms = 150, .jitter_ms = 20}),
                         [](const ::testing::TestParamInfo<RelayOptions>& info) {
                           return "OneWay" +
                                  std::to_string(static_cast<int>(info.param.one_way_ms)) + "Ms";
                         });

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
  const nlohmann::json summary =
      DriveOperator("127.0.0.1:" + std::to_string((*relay)->port()), "press", 1.5);
  ASSERT_TRUE(summary.is_object());
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

#include "client/loadtest/loadtest_command.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sstream>

#include "client/exit_codes.h"
#include "tests/server/test_server.h"

namespace hs::cli {
namespace {

void ExpectOrdered(const Percentiles& p, const std::string& what) {
  EXPECT_GT(p.count, 0) << what;
  EXPECT_GT(p.p50, 0) << what;
  EXPECT_LE(p.p50, p.p99) << what;
  EXPECT_LE(p.p99, p.p999) << what;
  EXPECT_LE(p.p999, p.max) << what;
}

// Two devices at 200 Hz into copies of the small test scene's tool.
LoadtestOptions TwoDevices(const hs::testing::TestServer& server) {
  LoadtestOptions options;
  options.server.address = server.address();
  options.clients = 2;
  options.rate_hz = 200;
  options.scene = hs::testing::SmallScene("base");
  return options;
}

// A small bounded run (2 devices x 200 Hz x 1 s, one viewer, the small
// test scene stepping at 2 kHz) checks its own arithmetic: every pose sent is answered once,
// per-device counts add up to the totals, each stream's frames plus drops
// cover its step range, percentiles are ordered, and the echo baseline ran
// with as many round trips.
TEST(LoadtestCommandTest, SmallRunAddsUp) {
  hs::testing::TestServer server;
  LoadtestOptions options = TwoDevices(server);
  options.duration_s = 1;
  options.viewers = 1;
  options.needs = {Effect::kForce, Effect::kFriction};  // what a haptic device reads
  options.step_s = 0.0005;
  absl::StatusOr<LoadReport> report = RunLoadtest(options);
  ASSERT_TRUE(report.ok()) << report.status();
  const LoadReport& r = *report;
  ASSERT_EQ(r.per_device.size(), 2u);
  int64_t sent = 0, answered = 0, frames = 0, dropped = 0;
  for (const StreamReport& d : r.per_device) {
    EXPECT_EQ(d.sent, 200);
    EXPECT_EQ(d.answered, d.sent);
    EXPECT_EQ(d.rtt_ms.count, d.answered);
    EXPECT_EQ(d.frames + d.dropped_frames, d.last_step - d.first_step + 1);
    ExpectOrdered(d.rtt_ms, "device");
    sent += d.sent;
    answered += d.answered;
    frames += d.frames;
    dropped += d.dropped_frames;
  }
  EXPECT_EQ(r.devices.sent, sent);
  EXPECT_EQ(r.devices.answered, answered);
  EXPECT_EQ(r.devices.frames, frames);
  EXPECT_EQ(r.devices.dropped_frames, dropped);
  EXPECT_EQ(r.devices.rtt_ms.count, answered);
  ExpectOrdered(r.devices.rtt_ms, "devices");
  EXPECT_EQ(r.viewers_total.frames + r.viewers_total.dropped_frames,
            r.viewers_total.last_step - r.viewers_total.first_step + 1);
  EXPECT_GT(r.viewers_total.frames, 0);
  ASSERT_TRUE(r.echo_run);
  EXPECT_EQ(r.echo.sent, 400);
  EXPECT_EQ(r.echo.answered, 400);
  EXPECT_EQ(r.echo.frames, 400);
  ExpectOrdered(r.echo.rtt_ms, "echo");
  EXPECT_GT(r.echo_request_bytes, 0);
  EXPECT_GT(r.echo_reply_bytes, 0);
  EXPECT_NEAR(r.p99_ratio, r.devices.rtt_ms.p99 / r.echo.rtt_ms.p99, 1e-12);
  ExpectOrdered(r.step_ms, "step");
  EXPECT_GE(r.missed_fraction, 0);
  EXPECT_LE(r.missed_fraction, 1);
  EXPECT_GE(r.missed_steps_off_cpu, 0);
  EXPECT_LE(r.missed_steps_off_cpu, r.missed_steps);
  // The in-process server is found by its port: this process.
  EXPECT_GE(r.server_cpu_percent, 0);
  // /proc/stat is there on Linux: the hypervisor's share is known (maybe 0).
  EXPECT_GE(r.machine_steal_ms, 0);
  // The scene is gone afterwards.
  EXPECT_EQ(server.server().registry().List().size(), 0u);
  // The JSON report holds the same figures.
  const nlohmann::json json = nlohmann::json::parse(LoadReportJson(r));
  EXPECT_EQ(json["devices"]["sent"].get<int64_t>(), sent);
  EXPECT_EQ(json["per_device"].size(), 2u);
  EXPECT_EQ(json["needs"], "force friction");
  EXPECT_EQ(json["step_s"].get<double>(), 0.0005);
  EXPECT_EQ(json["missed_steps_off_cpu"].get<int64_t>(), r.missed_steps_off_cpu);
}

// --tools-meet: the two devices' tools meet at every press, and the report
// counts the clashes (device 0's frames hold the pair's) and their time.
TEST(LoadtestCommandTest, ToolsMeetInPairs) {
  hs::testing::TestServer server;
  LoadtestOptions options = TwoDevices(server);
  options.duration_s = 2;
  options.echo = false;
  options.tools_meet = true;
  absl::StatusOr<LoadReport> report = RunLoadtest(options);
  ASSERT_TRUE(report.ok()) << report.status();
  EXPECT_TRUE(report->tools_meet);
  EXPECT_GE(report->tool_clashes, 1);
  EXPECT_LE(report->tool_clashes, 3);  // one a press, give or take the window's ends
  EXPECT_GT(report->tool_clash_s, 0.01);
  EXPECT_EQ(report->per_device[0].tool_clashes, report->tool_clashes);
  const nlohmann::json json = nlohmann::json::parse(LoadReportJson(*report));
  EXPECT_EQ(json["tool_clashes"].get<int64_t>(), report->tool_clashes);
}

// Options past the bounds and a remote server are usage errors; a scene
// without a tool is refused before anything is sent.
TEST(LoadtestCommandTest, Bounds) {
  std::ostringstream out, err;
  LoadtestArgs args;
  args.options.clients = 65;
  EXPECT_EQ(RunLoadtestCommand(args, out, err), kExitUsage);
  args.options.clients = 1;
  args.options.duration_s = 61;
  EXPECT_EQ(RunLoadtestCommand(args, out, err), kExitUsage);
  args.options.duration_s = 0.0004;  // at 1 kHz: no pose to send
  EXPECT_EQ(RunLoadtestCommand(args, out, err), kExitUsage);
  EXPECT_NE(err.str().find("at least one pose"), std::string::npos) << err.str();
  args.options.duration_s = 1;
  args.options.rate_hz = 10001;
  EXPECT_EQ(RunLoadtestCommand(args, out, err), kExitUsage);
  args.options.rate_hz = 1000;
  for (const double step_s : {0.00009, 1.5, -1.0}) {
    args.options.step_s = step_s;
    EXPECT_EQ(RunLoadtestCommand(args, out, err), kExitUsage) << step_s;
  }
  EXPECT_NE(err.str().find("--step-s"), std::string::npos) << err.str();
  args.options.step_s = 0;
  args.needs = {"gravity"};
  EXPECT_EQ(RunLoadtestCommand(args, out, err), kExitUsage);
  EXPECT_NE(err.str().find("gravity"), std::string::npos) << err.str();
  args.needs.clear();
  args.options.server.address = "192.0.2.1:50051";
  EXPECT_EQ(RunLoadtestCommand(args, out, err), kExitUsage);
  EXPECT_NE(err.str().find("--allow-remote"), std::string::npos) << err.str();
  haptics::v1::SceneSpec no_tool = hs::testing::SmallScene("x");
  no_tool.mutable_objects()->RemoveLast();
  EXPECT_FALSE(LoadtestScene(no_tool, 2, "y").ok());
  const absl::StatusOr<haptics::v1::SceneSpec> copies =
      LoadtestScene(hs::testing::SmallScene("x"), 3, "y");
  ASSERT_TRUE(copies.ok());
  EXPECT_EQ(copies->objects_size(), 4);
  EXPECT_EQ(copies->objects(3).name(), "tool-2");
}

}  // namespace
}  // namespace hs::cli

#include "client/loadtest/loadtest.h"

#include <gtest/gtest.h>

#include "tests/client/loadtest/metrics_endpoint.h"
#include "tests/server/test_server.h"

namespace hs::cli {
namespace {

// Two devices at 100 Hz for half a second on the small test scene, no echo.
LoadtestOptions Small(const hs::testing::TestServer& server) {
  LoadtestOptions options;
  options.server.address = server.address();
  options.clients = 2;
  options.rate_hz = 100;
  options.duration_s = 0.5;
  options.echo = false;
  options.scene = hs::testing::SmallScene("base");
  return options;
}

// The server's CPU per device is its CPU over the devices' turns divided
// among them; the in-process server is read through /proc. The devices
// ask for half the scene's frames: every pose is still answered.
TEST(LoadtestTest, ServerCpuPerDeviceFromProc) {
  hs::testing::TestServer server;
  LoadtestOptions options = Small(server);
  options.frame_rate_hz = 500;
  const absl::StatusOr<LoadReport> report = RunLoadtest(options);
  ASSERT_TRUE(report.ok()) << report.status();
  EXPECT_EQ(report->devices.sent, 100);
  EXPECT_EQ(report->devices.answered, 100);
  ASSERT_GE(report->server_cpu_percent, 0);
  EXPECT_DOUBLE_EQ(report->server_cpu_percent_per_device, report->server_cpu_percent / 2);
  EXPECT_EQ(report->server_cpu_source.rfind("/proc/", 0), 0u) << report->server_cpu_source;
  EXPECT_FALSE(report->echo_run);
}

// With a metrics endpoint the server's CPU is its process_cpu_seconds_total
// there: a counter that stands still is 0 %.
TEST(LoadtestTest, ServerCpuFromMetrics) {
  hs::testing::TestServer server;
  hs::testing::MetricsEndpoint endpoint(42);
  LoadtestOptions options = Small(server);
  options.server_metrics_url = endpoint.url();
  const absl::StatusOr<LoadReport> report = RunLoadtest(options);
  ASSERT_TRUE(report.ok()) << report.status();
  EXPECT_EQ(report->server_cpu_percent, 0);
  EXPECT_EQ(report->server_cpu_percent_per_device, 0);
  EXPECT_EQ(report->server_cpu_source, "process_cpu_seconds_total at " + endpoint.url());
}

// Failures come back as statuses: a scene without a tool before anything
// is sent, a server that does not answer with the request that failed.
TEST(LoadtestTest, Failures) {
  hs::testing::TestServer server;
  LoadtestOptions options = Small(server);
  options.scene->mutable_objects()->RemoveLast();
  EXPECT_EQ(RunLoadtest(options).status().code(), absl::StatusCode::kInvalidArgument);
  options = Small(server);
  options.server.address = "127.0.0.1:1";
  options.server.timeout_s = 2;
  const absl::StatusOr<LoadReport> unreachable = RunLoadtest(options);
  EXPECT_EQ(unreachable.status().code(), absl::StatusCode::kUnavailable);
  EXPECT_NE(unreachable.status().message().find("server: CreateScene"), std::string::npos)
      << unreachable.status();
  EXPECT_EQ(server.server().registry().List().size(), 0u);
}

}  // namespace
}  // namespace hs::cli

#include "client/loadtest/server_cpu.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include "absl/strings/str_cat.h"
#include "tests/client/loadtest/metrics_endpoint.h"
#include "tests/server/test_server.h"

namespace hs::cli {
namespace {

// With a metrics address the server's CPU seconds are its
// process_cpu_seconds_total there, read anew each time.
TEST(ServerCpuTest, FromTheMetricsEndpoint) {
  hs::testing::MetricsEndpoint endpoint(12.5);
  LoadtestOptions options;
  options.server_metrics_url = endpoint.url();
  options.server_pid = getpid();  // the endpoint wins
  const ServerCpuSource source = FindServerCpuSource(options);
  EXPECT_EQ(source.description, "process_cpu_seconds_total at " + endpoint.url());
  EXPECT_EQ(source.read(), 12.5);
  endpoint.AddCpuSeconds(1);
  EXPECT_EQ(source.read(), 13.5);
}

// An endpoint that stops answering gives no reading.
TEST(ServerCpuTest, EndpointGone) {
  LoadtestOptions options;
  {
    hs::testing::MetricsEndpoint endpoint(1);
    options.server_metrics_url = endpoint.url();
  }
  EXPECT_FALSE(FindServerCpuSource(options).read().has_value());
}

// A given pid is read through /proc; an in-process server is found by its
// loopback port: this process, and the report says so.
TEST(ServerCpuTest, FromProc) {
  hs::testing::TestServer server;
  LoadtestOptions options;
  options.server.address = server.address();
  const ServerCpuSource found = FindServerCpuSource(options);
  EXPECT_EQ(found.description,
            absl::StrCat("/proc/", getpid(), "/stat (this process: server and load generator)"));
  EXPECT_TRUE(found.read().has_value());
  options.server.address = "192.0.2.1:50051";
  options.server_pid = 1;
  EXPECT_EQ(FindServerCpuSource(options).description, "/proc/1/stat");
}

// A server off loopback without a pid or an endpoint has no source, and
// the description says what to give.
TEST(ServerCpuTest, NoSource) {
  LoadtestOptions options;
  options.server.address = "192.0.2.1:50051";
  const ServerCpuSource none = FindServerCpuSource(options);
  EXPECT_FALSE(none.read().has_value());
  EXPECT_NE(none.description.find("--server-metrics"), std::string::npos);
}

}  // namespace
}  // namespace hs::cli

#include "client/loadtest/metrics_scrape.h"

#include <gtest/gtest.h>

#include "tests/client/loadtest/metrics_endpoint.h"

namespace hs::cli {
namespace {

// http://HOST:PORT/PATH with a port in range passes; other schemes, no
// port, a port out of range or not a number are refused naming the flag.
TEST(MetricsScrapeTest, CheckUrl) {
  EXPECT_TRUE(CheckMetricsUrl("http://127.0.0.1:9464/metrics").ok());
  EXPECT_TRUE(CheckMetricsUrl("http://server.local:1/m").ok());
  EXPECT_TRUE(CheckMetricsUrl("http://[::1]:9464/metrics").ok());
  for (const char* bad : {"https://127.0.0.1:9464/metrics", "127.0.0.1:9464", "http://127.0.0.1/x",
                          "http://127.0.0.1:0/metrics", "http://127.0.0.1:65536/metrics",
                          "http://:9464/metrics", "http://127.0.0.1:port/metrics", ""}) {
    const absl::Status status = CheckMetricsUrl(bad);
    EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument) << bad;
    EXPECT_NE(status.message().find("--server-metrics"), std::string::npos) << status;
  }
}

// The body of a live endpoint is its text exposition.
TEST(MetricsScrapeTest, FetchesTheExposition) {
  hs::testing::MetricsEndpoint endpoint(12.5);
  const absl::StatusOr<std::string> text = FetchMetricsText(endpoint.url(), 5);
  ASSERT_TRUE(text.ok()) << text.status();
  EXPECT_NE(text->find("process_cpu_seconds_total 12.5"), std::string::npos) << *text;
}

// A path the endpoint does not serve, and a port nobody listens on, are
// UNAVAILABLE naming the url.
TEST(MetricsScrapeTest, Unavailable) {
  std::string url;
  {
    hs::testing::MetricsEndpoint endpoint(1);
    url = endpoint.url();
    const std::string wrong = url.substr(0, url.rfind('/')) + "/nothing";
    const absl::StatusOr<std::string> missing = FetchMetricsText(wrong, 5);
    EXPECT_EQ(missing.status().code(), absl::StatusCode::kUnavailable);
    EXPECT_NE(missing.status().message().find("/nothing"), std::string::npos);
  }
  const absl::StatusOr<std::string> gone = FetchMetricsText(url, 5);
  EXPECT_EQ(gone.status().code(), absl::StatusCode::kUnavailable) << gone.status();
}

}  // namespace
}  // namespace hs::cli

#include "client/loadtest/loadtest_options.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace hs::cli {
namespace {

// Expects `options` refused with a message containing `flag`.
void ExpectRefused(const LoadtestOptions& options, const std::string& flag) {
  const absl::Status status = CheckLoadtestOptions(options);
  EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument) << flag;
  EXPECT_NE(status.message().find(flag), std::string::npos) << status;
}

// The defaults pass; each bound is inclusive where documented and refused
// one past it, naming its flag.
TEST(LoadtestOptionsTest, Bounds) {
  EXPECT_TRUE(CheckLoadtestOptions({}).ok());
  LoadtestOptions o;
  o.clients = kMaxLoadClients;
  o.viewers = kMaxLoadViewers;
  o.duration_s = kMaxLoadSeconds;
  o.rate_hz = kMaxLoadRateHz;
  o.step_s = 1e-4;
  EXPECT_TRUE(CheckLoadtestOptions(o).ok());
  auto with = [](auto set) {
    LoadtestOptions options;
    set(options);
    return options;
  };
  ExpectRefused(with([](LoadtestOptions& x) { x.clients = 0; }), "--clients");
  ExpectRefused(with([](LoadtestOptions& x) { x.clients = kMaxLoadClients + 1; }), "--clients");
  ExpectRefused(with([](LoadtestOptions& x) { x.viewers = -1; }), "--viewers");
  ExpectRefused(with([](LoadtestOptions& x) { x.duration_s = 0; }), "--duration");
  ExpectRefused(with([](LoadtestOptions& x) { x.rate_hz = kMaxLoadRateHz + 1; }), "--rate");
  ExpectRefused(with([](LoadtestOptions& x) { x.step_s = 2; }), "--step-s");
  ExpectRefused(with([](LoadtestOptions& x) { x.duration_s = 1e-4; }), "at least one pose");
  ExpectRefused(with([](LoadtestOptions& x) { x.planes = true; }), "--planes");
  EXPECT_TRUE(CheckLoadtestOptions(with([](LoadtestOptions& x) {
                x.planes = true;
                x.needs = x.needs.With(Effect::kLocalModel);
              })).ok());
  ExpectRefused(with([](LoadtestOptions& x) { x.server.address = "192.0.2.1:1"; }),
                "--allow-remote");
  LoadtestOptions remote;
  remote.server.address = "192.0.2.1:1";
  remote.allow_remote = true;
  EXPECT_TRUE(CheckLoadtestOptions(remote).ok());
}

// The frame rate is the server's own (0) or within --frame-rate-hz's
// bounds; --rate, the poses sent, is checked apart from it.
TEST(LoadtestOptionsTest, FrameRate) {
  LoadtestOptions o;
  o.frame_rate_hz = 100000;
  o.rate_hz = 1;
  EXPECT_TRUE(CheckLoadtestOptions(o).ok());
  for (const double bad : {0.5, 100001.0, std::numeric_limits<double>::quiet_NaN(),
                           std::numeric_limits<double>::infinity()}) {
    o.frame_rate_hz = bad;
    ExpectRefused(o, "--frame-rate-hz");
  }
}

// A metrics address must be http://HOST:PORT/PATH.
TEST(LoadtestOptionsTest, MetricsUrl) {
  LoadtestOptions o;
  o.server_metrics_url = "http://127.0.0.1:9464/metrics";
  EXPECT_TRUE(CheckLoadtestOptions(o).ok());
  o.server_metrics_url = "127.0.0.1:9464";
  ExpectRefused(o, "--server-metrics");
}

}  // namespace
}  // namespace hs::cli

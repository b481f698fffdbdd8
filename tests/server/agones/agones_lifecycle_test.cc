// The Agones SDK client and the game server's lifecycle against a stand-in
// for the SDK's REST endpoint that records what it receives: the requests
// Agones documents, in the order a game server owes them, and a failing
// SDK that is counted, logged once and retried while nothing else changes.

#include "server/agones/agones_lifecycle.h"

#include <gtest/gtest.h>

#include <mutex>
#include <sstream>
#include <thread>

#include "server/agones/agones_sdk.h"
#include "tests/server/agones/fake_agones_sdk.h"

namespace hs {
namespace {

using testing::FakeAgonesSdk;

TEST(AgonesLabelValueTest, MakesKubernetesLabelValues) {
  EXPECT_EQ(AgonesLabelValue("probe on torus"), "probe-on-torus");
  EXPECT_EQ(AgonesLabelValue("  Liver #2 (left) "), "liver-2-left");
  EXPECT_EQ(AgonesLabelValue("A.b_c-d"), "a.b_c-d");
  EXPECT_EQ(AgonesLabelValue("__x__"), "x");
  EXPECT_EQ(AgonesLabelValue("///"), "");
  EXPECT_EQ(AgonesLabelValue(""), "");
  EXPECT_EQ(AgonesLabelValue(std::string(70, 'a')), std::string(63, 'a'));
  // Cut at 63, then no '-' left at the end.
  EXPECT_EQ(AgonesLabelValue(std::string(62, 'a') + " b"), std::string(62, 'a'));
}

TEST(AgonesSdkTest, SendsTheDocumentedRequests) {
  FakeAgonesSdk fake;
  AgonesSdk sdk(fake.port());
  EXPECT_TRUE(sdk.Ready().ok());
  EXPECT_TRUE(sdk.Health().ok());
  EXPECT_TRUE(sdk.SetLabel("scene", "probe-on-torus").ok());
  EXPECT_TRUE(sdk.Allocate().ok());
  EXPECT_TRUE(sdk.Shutdown().ok());
  const std::vector<FakeAgonesSdk::Request> got = fake.requests();
  ASSERT_EQ(got.size(), 5u);
  const std::vector<std::pair<std::string, std::string>> expected = {{"POST", "/ready"},
                                                                     {"POST", "/health"},
                                                                     {"PUT", "/metadata/label"},
                                                                     {"POST", "/allocate"},
                                                                     {"POST", "/shutdown"}};
  for (size_t i = 0; i < got.size(); ++i) {
    EXPECT_EQ(got[i].method, expected[i].first);
    EXPECT_EQ(got[i].target, expected[i].second);
  }
  EXPECT_EQ(got[2].body, R"({"key":"scene","value":"probe-on-torus"})");
  EXPECT_EQ(got[0].body, "{}");
}

TEST(AgonesSdkTest, FailuresAreUnavailable) {
  FakeAgonesSdk fake;
  fake.SetFailing(true);
  const absl::Status refused = AgonesSdk(fake.port()).Ready();
  EXPECT_EQ(refused.code(), absl::StatusCode::kUnavailable);
  EXPECT_NE(refused.message().find("HTTP 503"), std::string::npos) << refused;
  int closed_port = 0;
  {
    FakeAgonesSdk gone;
    closed_port = gone.port();
  }
  const absl::Status unreachable = AgonesSdk(closed_port, 0.5).Health();
  EXPECT_EQ(unreachable.code(), absl::StatusCode::kUnavailable);
}

// The server as the lifecycle sees it, set by the test.
class FakeServer {
 public:
  void Set(int devices, int viewers) {
    std::lock_guard lock(mu_);
    activity_.devices = devices;
    activity_.viewers = viewers;
  }
  ServerActivity Get() {
    std::lock_guard lock(mu_);
    return activity_;
  }

 private:
  std::mutex mu_;
  ServerActivity activity_{.scene = "Probe on torus"};
};

AgonesOptions Fast(int port) {
  return {.sdk_port = port, .health_interval_s = 0.05, .idle_shutdown_s = 0.3, .poll_s = 0.01};
}

// Ready, the label and health pings at once; Allocate only when a device
// (not a viewer) joins, once; Shutdown only after every client has left
// and the idle time passed.
TEST(AgonesLifecycleTest, ReadyLabelAllocateShutdown) {
  FakeAgonesSdk fake;
  FakeServer server;
  Metrics metrics;
  std::ostringstream log;
  AgonesLifecycle lifecycle(
      Fast(fake.port()), [&] { return server.Get(); }, metrics, log);
  ASSERT_TRUE(fake.WaitFor("POST", "/ready"));
  ASSERT_TRUE(fake.WaitFor("PUT", "/metadata/label"));
  ASSERT_TRUE(fake.WaitFor("POST", "/health", 3));
  for (const FakeAgonesSdk::Request& r : fake.requests()) {
    if (r.target == "/metadata/label") {
      EXPECT_EQ(r.body, R"({"key":"scene","value":"probe-on-torus"})");
    }
  }
  server.Set(0, 1);  // a viewer alone: not allocated
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  EXPECT_EQ(fake.Count("POST", "/allocate"), 0);
  server.Set(1, 1);
  ASSERT_TRUE(fake.WaitFor("POST", "/allocate"));
  server.Set(0, 0);
  const auto left = std::chrono::steady_clock::now();
  ASSERT_TRUE(fake.WaitFor("POST", "/shutdown"));
  EXPECT_GE(std::chrono::steady_clock::now() - left, std::chrono::milliseconds(300));
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  EXPECT_EQ(fake.Count("POST", "/allocate"), 1);
  EXPECT_EQ(fake.Count("POST", "/shutdown"), 1);
  EXPECT_EQ(fake.Count("POST", "/ready"), 1);
  EXPECT_EQ(fake.Count("PUT", "/metadata/label"), 1);
  EXPECT_NE(metrics.Text().find("hs_agones_sdk_up 1"), std::string::npos);
}

// A server no client has joined waits in the fleet's buffer: no shutdown.
// A client that comes back within the idle time keeps it.
TEST(AgonesLifecycleTest, IdleShutdownNeedsAClientToHaveLeft) {
  FakeAgonesSdk fake;
  FakeServer server;
  Metrics metrics;
  std::ostringstream log;
  AgonesOptions options = Fast(fake.port());
  options.idle_shutdown_s = 1;
  AgonesLifecycle lifecycle(
      options, [&] { return server.Get(); }, metrics, log);
  ASSERT_TRUE(fake.WaitFor("POST", "/ready"));
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  EXPECT_EQ(fake.Count("POST", "/shutdown"), 0);
  server.Set(0, 1);
  ASSERT_TRUE(fake.WaitFor("POST", "/health", fake.Count("POST", "/health") + 2));
  server.Set(0, 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  server.Set(0, 1);  // back within the idle time
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  EXPECT_EQ(fake.Count("POST", "/shutdown"), 0);
}

// An SDK that fails: every call is counted as an error and hs_agones_sdk_up
// is 0, the log says so once, and the lifecycle goes on where it was when
// the SDK answers again.
TEST(AgonesLifecycleTest, FailingSdkIsCountedLoggedAndRetried) {
  FakeAgonesSdk fake;
  fake.SetFailing(true);
  FakeServer server;
  Metrics metrics;
  std::ostringstream log;
  {
    AgonesLifecycle lifecycle(
        Fast(fake.port()), [&] { return server.Get(); }, metrics, log);
    ASSERT_TRUE(fake.WaitFor("POST", "/ready", 2));  // retried
    ASSERT_TRUE(fake.WaitFor("POST", "/health", 3));
    const std::string failing = metrics.Text();
    EXPECT_NE(failing.find("hs_agones_sdk_up 0"), std::string::npos) << failing;
    EXPECT_NE(failing.find(R"(hs_agones_sdk_requests_total{call="ready",result="error"})"),
              std::string::npos)
        << failing;
    fake.SetFailing(false);
    ASSERT_TRUE(fake.WaitFor("PUT", "/metadata/label"));
    // Ready was answered: it is not sent again.
    const int ready = fake.Count("POST", "/ready");
    ASSERT_TRUE(fake.WaitFor("POST", "/health", fake.Count("POST", "/health") + 3));
    EXPECT_EQ(fake.Count("POST", "/ready"), ready);
    EXPECT_NE(metrics.Text().find("hs_agones_sdk_up 1"), std::string::npos);
  }
  const std::string text = log.str();
  const size_t first = text.find("clients are served as usual");
  ASSERT_NE(first, std::string::npos) << text;
  EXPECT_EQ(text.find("clients are served as usual", first + 1), std::string::npos) << text;
  EXPECT_NE(text.find("Agones SDK answers again"), std::string::npos) << text;
}

}  // namespace
}  // namespace hs

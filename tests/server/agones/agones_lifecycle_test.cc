// The game server's lifecycle against a stand-in for the SDK's REST
// endpoint that records what it receives: the requests Agones documents, in
// the order a game server owes them, and a failing SDK that is counted,
// logged once and retried while nothing else changes.

#include "server/agones/agones_lifecycle.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <mutex>
#include <sstream>
#include <thread>

#include "tests/server/agones/fake_agones_sdk.h"

namespace hs {
namespace {

using testing::FakeAgonesSdk;

// The server as the lifecycle sees it, set by the test.
class FakeServer {
 public:
  // Devices and viewers attached now; those above the last counts joined.
  void Set(int devices, int viewers) {
    std::lock_guard lock(mu_);
    activity_.devices_joined += std::max(0, devices - activity_.devices);
    activity_.viewers_joined += std::max(0, viewers - activity_.viewers);
    activity_.devices = devices;
    activity_.viewers = viewers;
  }
  // A device that joined and left between two polls.
  void Visit() {
    std::lock_guard lock(mu_);
    ++activity_.devices_joined;
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

// A lifecycle against the stand-in SDK and a server the test sets.
class AgonesLifecycleTest : public ::testing::Test {
 protected:
  void Start(const AgonesOptions& options) {
    lifecycle_ = std::make_unique<AgonesLifecycle>(
        options, [this] { return server_.Get(); }, metrics_, log_);
  }
  void Start() { Start(Fast(fake_.port())); }

  FakeAgonesSdk fake_;
  FakeServer server_;
  Metrics metrics_;
  std::ostringstream log_;
  std::unique_ptr<AgonesLifecycle> lifecycle_;
};

// Ready, the label and health pings at once; Allocate only when a device
// (not a viewer) joins, once; Shutdown only after every client has left
// and the idle time passed.
TEST_F(AgonesLifecycleTest, ReadyLabelAllocateShutdown) {
  Start();
  ASSERT_TRUE(fake_.WaitFor("POST", "/ready"));
  ASSERT_TRUE(fake_.WaitFor("PUT", "/metadata/label"));
  ASSERT_TRUE(fake_.WaitFor("POST", "/health", 3));
  for (const FakeAgonesSdk::Request& r : fake_.requests()) {
    if (r.target == "/metadata/label") {
      EXPECT_EQ(r.body, R"({"key":"scene","value":"probe-on-torus"})");
    }
  }
  server_.Set(0, 1);  // a viewer alone: not allocated
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  EXPECT_EQ(fake_.Count("POST", "/allocate"), 0);
  server_.Set(1, 1);
  ASSERT_TRUE(fake_.WaitFor("POST", "/allocate"));
  server_.Set(0, 0);
  const auto left = std::chrono::steady_clock::now();
  ASSERT_TRUE(fake_.WaitFor("POST", "/shutdown"));
  EXPECT_GE(std::chrono::steady_clock::now() - left, std::chrono::milliseconds(300));
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  EXPECT_EQ(fake_.Count("POST", "/allocate"), 1);
  EXPECT_EQ(fake_.Count("POST", "/shutdown"), 1);
  EXPECT_EQ(fake_.Count("POST", "/ready"), 1);
  EXPECT_EQ(fake_.Count("PUT", "/metadata/label"), 1);
  EXPECT_NE(metrics_.Text().find("hs_agones_sdk_up 1"), std::string::npos);
}

// A server no client has joined waits in the fleet's buffer: no shutdown.
// A client that comes back within the idle time keeps it.
TEST_F(AgonesLifecycleTest, IdleShutdownNeedsAClientToHaveLeft) {
  AgonesOptions options = Fast(fake_.port());
  options.idle_shutdown_s = 1;
  Start(options);
  ASSERT_TRUE(fake_.WaitFor("POST", "/ready"));
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  EXPECT_EQ(fake_.Count("POST", "/shutdown"), 0);
  server_.Set(0, 1);
  ASSERT_TRUE(fake_.WaitFor("POST", "/health", fake_.Count("POST", "/health") + 2));
  server_.Set(0, 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  server_.Set(0, 1);  // back within the idle time
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  EXPECT_EQ(fake_.Count("POST", "/shutdown"), 0);
}

// A device that came and went between two polls is still seen: the server
// is allocated, and shut down once idle.
TEST_F(AgonesLifecycleTest, AVisitBetweenPollsCounts) {
  Start();
  ASSERT_TRUE(fake_.WaitFor("POST", "/ready"));
  server_.Visit();
  EXPECT_TRUE(fake_.WaitFor("POST", "/allocate"));
  EXPECT_TRUE(fake_.WaitFor("POST", "/shutdown"));
}

// An SDK that fails: every call is counted as an error and hs_agones_sdk_up
// is 0, the log says so once, and the lifecycle goes on where it was when
// the SDK answers again.
TEST_F(AgonesLifecycleTest, FailingSdkIsCountedLoggedAndRetried) {
  fake_.SetFailing(true);
  Start();
  {
    ASSERT_TRUE(fake_.WaitFor("POST", "/ready", 2));  // retried
    ASSERT_TRUE(fake_.WaitFor("POST", "/health", 3));
    const std::string failing = metrics_.Text();
    EXPECT_NE(failing.find("hs_agones_sdk_up 0"), std::string::npos) << failing;
    EXPECT_NE(failing.find(R"(hs_agones_sdk_requests_total{call="ready",result="error"})"),
              std::string::npos)
        << failing;
    fake_.SetFailing(false);
    ASSERT_TRUE(fake_.WaitFor("PUT", "/metadata/label"));
    // Ready was answered: it is not sent again.
    const int ready = fake_.Count("POST", "/ready");
    ASSERT_TRUE(fake_.WaitFor("POST", "/health", fake_.Count("POST", "/health") + 3));
    EXPECT_EQ(fake_.Count("POST", "/ready"), ready);
    EXPECT_NE(metrics_.Text().find("hs_agones_sdk_up 1"), std::string::npos);
  }
  lifecycle_.reset();  // its last words in the log
  const std::string text = log_.str();
  const size_t first = text.find("clients are served as usual");
  ASSERT_NE(first, std::string::npos) << text;
  EXPECT_EQ(text.find("clients are served as usual", first + 1), std::string::npos) << text;
  EXPECT_NE(text.find("Agones SDK answers again"), std::string::npos) << text;
}

}  // namespace
}  // namespace hs

// The Agones SDK client against a stand-in for the SDK's REST endpoint
// that records what it receives.

#include "server/agones/agones_sdk.h"

#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "tests/server/agones/fake_agones_sdk.h"

namespace hs {
namespace {

using testing::FakeAgonesSdk;

// Text becomes a Kubernetes label value: lower case, runs of other
// characters one '-', trimmed to 63 characters and to a letter or digit.
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

// Each call is the request Agones documents: method, path and body.
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

// An answer other than 2xx, or no endpoint at all, is UNAVAILABLE.
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

}  // namespace
}  // namespace hs

#include "server/caller_quotas.h"

#include <gtest/gtest.h>

namespace hs {
namespace {

// Each caller takes up to its limit of each quota and no more, apart from
// other callers and other quotas; what it gives back it may take again.
TEST(CallerQuotasTest, TakeUpToTheLimitPerCallerAndQuota) {
  CallerQuotas quotas(CallerLimits{.streams = 2, .uploads_in_flight = 1, .models = 3, .scenes = 1});
  EXPECT_TRUE(quotas.Take("a", Quota::kStreams).ok());
  EXPECT_TRUE(quotas.Take("a", Quota::kStreams).ok());
  const absl::Status third = quotas.Take("a", Quota::kStreams);
  EXPECT_EQ(third.code(), absl::StatusCode::kResourceExhausted);
  EXPECT_EQ(third.message(), "at most 2 open streams per caller");
  EXPECT_TRUE(quotas.Take("b", Quota::kStreams).ok());
  EXPECT_TRUE(quotas.Take("a", Quota::kScenes).ok());
  EXPECT_EQ(quotas.Take("a", Quota::kScenes).code(), absl::StatusCode::kResourceExhausted);
  quotas.Give("a", Quota::kStreams);
  EXPECT_EQ(quotas.held("a", Quota::kStreams), 1);
  EXPECT_TRUE(quotas.Take("a", Quota::kStreams).ok());
  quotas.Give("nobody", Quota::kStreams);  // nothing held: nothing happens
  EXPECT_EQ(quotas.held("nobody", Quota::kStreams), 0);
}

// A quota owned by a named thing goes back to the caller that took it,
// whoever ends the thing, once.
TEST(CallerQuotasTest, DisownGivesBackToTheOwner) {
  CallerQuotas quotas(CallerLimits{.scenes = 1});
  ASSERT_TRUE(quotas.Take("a", Quota::kScenes).ok());
  quotas.Own("a", Quota::kScenes, "lab");
  EXPECT_EQ(quotas.Take("a", Quota::kScenes).code(), absl::StatusCode::kResourceExhausted);
  quotas.Disown(Quota::kScenes, "lab");
  EXPECT_EQ(quotas.held("a", Quota::kScenes), 0);
  quotas.Disown(Quota::kScenes, "lab");  // twice: nothing more
  quotas.Disown(Quota::kScenes, "never-owned");
  EXPECT_EQ(quotas.held("a", Quota::kScenes), 0);
  EXPECT_TRUE(quotas.Take("a", Quota::kScenes).ok());
}

}  // namespace
}  // namespace hs

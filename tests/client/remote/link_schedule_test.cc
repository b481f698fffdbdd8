#include "client/remote/link_schedule.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <vector>

namespace hs::cli {
namespace {

// The release times of `n` messages sent 1 ms apart from 0 (the lost ones left out).
std::vector<double> Releases(LinkSchedule& schedule, int n) {
  std::vector<double> at;
  for (int i = 0; i < n; ++i) {
    if (std::optional<double> t = schedule.Release(i * 1e-3)) at.push_back(*t);
  }
  return at;
}
std::vector<double> Releases(const LinkConditions& link, int n) {
  LinkSchedule schedule(link, 0);
  return Releases(schedule, n);
}

// Without jitter, losses or stalls each message is held exactly half the
// round trip.
TEST(LinkScheduleTest, HoldsHalfTheRoundTrip) {
  const std::vector<double> at = Releases({.latency_ms = 40}, 10);
  ASSERT_EQ(at.size(), 10u);
  for (int i = 0; i < 10; ++i) EXPECT_DOUBLE_EQ(at[i], i * 1e-3 + 0.020);
}

// Every message stalled: each comes out the one-way time plus the stall
// after it went in.
TEST(LinkScheduleTest, CertainStallAddsItsTime) {
  LinkSchedule schedule({.latency_ms = 10, .stall_prob = 1, .stall_ms = 30}, 0);
  for (int i = 0; i < 5; ++i) EXPECT_DOUBLE_EQ(*schedule.Release(i * 1e-3), i * 1e-3 + 0.035);
  EXPECT_EQ(schedule.stalled(), 5);
}

// A stall holds the messages behind it: the message after a stalled one
// comes out no earlier than it, though it was not stalled itself; release
// times never decrease; the stall count matches the probability.
TEST(LinkScheduleTest, StallHoldsTheMessagesBehindIt) {
  const LinkConditions link{
      .latency_ms = 20, .jitter_ms = 4, .stall_prob = 0.02, .stall_ms = 50, .seed = 3};
  LinkSchedule schedule(link, 0);
  const std::vector<double> at = Releases(schedule, 2000);
  ASSERT_EQ(at.size(), 2000u);
  EXPECT_TRUE(std::is_sorted(at.begin(), at.end()));
  EXPECT_GT(schedule.stalled(), 20);
  EXPECT_LT(schedule.stalled(), 60);
  // Messages held past their own one-way + jitter bound: only a stall, or
  // a stalled message ahead of them, can do that.
  int held_behind = 0;
  for (int i = 0; i < 2000; ++i) held_behind += at[i] > i * 1e-3 + 0.010 + 0.004 + 1e-12;
  EXPECT_GT(held_behind, 2 * schedule.stalled());  // each stall holds the next ~50 too
  EXPECT_EQ(schedule.lost(), 0);
}

// The same seed gives the same releases; another seed or stream others.
TEST(LinkScheduleTest, RepeatsWithTheSeed) {
  const LinkConditions link{.latency_ms = 20,
                            .jitter_ms = 4,
                            .loss = 0.05,
                            .stall_prob = 0.05,
                            .stall_ms = 50,
                            .seed = 9};
  EXPECT_EQ(Releases(link, 500), Releases(link, 500));
  LinkConditions other = link;
  other.seed = 10;
  EXPECT_NE(Releases(link, 500), Releases(other, 500));
}

// A link without stalls draws the same numbers whatever the stall time:
// adding the option changes no existing run.
TEST(LinkScheduleTest, NoStallsLeaveTheDrawsAlone) {
  const LinkConditions link{.latency_ms = 20, .jitter_ms = 4, .loss = 0.1, .seed = 5};
  LinkConditions zero_prob = link;
  zero_prob.stall_ms = 100;
  EXPECT_EQ(Releases(link, 500), Releases(zero_prob, 500));
}

// Probabilities outside [0, 1], negative, too long or non-finite times are
// refused, naming the field.
TEST(LinkScheduleTest, ChecksTheConditions) {
  EXPECT_TRUE(CheckLinkConditions({.latency_ms = 100, .stall_prob = 1, .stall_ms = 200}).ok());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (const LinkConditions& bad :
       {LinkConditions{.stall_prob = -0.1}, LinkConditions{.stall_prob = 1.5},
        LinkConditions{.stall_prob = nan}, LinkConditions{.stall_ms = -1},
        LinkConditions{.stall_ms = nan}, LinkConditions{.stall_ms = inf},
        LinkConditions{.stall_ms = kMaxLinkMs + 1}}) {
    const absl::Status status = CheckLinkConditions(bad);
    EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument);
    EXPECT_NE(status.message().find("stall"), std::string::npos) << status.message();
  }
  EXPECT_FALSE(CheckLinkConditions({.latency_ms = nan}).ok());
  EXPECT_FALSE(CheckLinkConditions({.jitter_ms = -1}).ok());
  EXPECT_FALSE(CheckLinkConditions({.loss = 2}).ok());
}

}  // namespace
}  // namespace hs::cli

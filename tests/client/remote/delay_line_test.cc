#include "client/remote/delay_line.h"

#include <gtest/gtest.h>

#include <vector>

namespace hs::cli {
namespace {

// 30 ms round trip holds each message 15 ms; jitter adds up to its value;
// order is kept; the same seed loses the same messages.
TEST(DelayLineTest, HoldsInOrderAndRepeatsWithTheSeed) {
  const LinkConditions link{.latency_ms = 30, .jitter_ms = 5, .loss = 0.1, .seed = 7};
  std::vector<int> first, second;
  for (std::vector<int>* out : {&first, &second}) {
    DelayLine<int> line(link, 0);
    for (int i = 0; i < 1000; ++i) {
      line.Push(i * 1e-3, i);
      line.PopDue(i * 1e-3, [&](int v) { out->push_back(v); });
    }
    line.PopDue(10, [&](int v) { out->push_back(v); });
    EXPECT_GE(line.mean_delay_s(), 0.015);
    EXPECT_LE(line.max_delay_s(), 0.020 + 1e-3);  // 15 ms, 5 ms jitter, in order
    EXPECT_GT(line.lost(), 50);
    EXPECT_LT(line.lost(), 150);
  }
  EXPECT_EQ(first, second);
  EXPECT_TRUE(std::is_sorted(first.begin(), first.end()));
}

// A message stalled 50 ms holds the ones sent after it: they come out in
// order, and the one sent 1 ms after a stalled message is held past its
// own 10 ms. The same seed stalls the same messages.
TEST(DelayLineTest, StallHoldsTheMessagesBehindIt) {
  const LinkConditions link{.latency_ms = 20, .stall_prob = 0.01, .stall_ms = 50, .seed = 4};
  std::vector<std::pair<int, double>> first, second;
  for (auto* out : {&first, &second}) {
    DelayLine<int> line(link, 1);
    for (int i = 0; i < 2000; ++i) {
      line.Push(i * 1e-3, i);
      line.PopDue(i * 1e-3, [&](int v) { out->emplace_back(v, i * 1e-3); });
    }
    line.PopDue(10, [&](int v) { out->emplace_back(v, 10.0); });
    EXPECT_GT(line.stalled(), 5);
    EXPECT_GE(line.max_delay_s(), 0.060 - 1e-9);
  }
  EXPECT_EQ(first, second);
  ASSERT_EQ(first.size(), 2000u);
  int held = 0;
  for (int i = 0; i < 2000; ++i) {
    EXPECT_EQ(first[i].first, i);
    held += first[i].second > i * 1e-3 + 0.010 + 1e-9;
  }
  EXPECT_GT(held, 50);  // more than the stalled ones alone
}

TEST(DelayLineTest, IdealLinkDeliversAtOnce) {
  DelayLine<int> line(LinkConditions{}, 0);
  line.Push(0.5, 1);
  int got = 0;
  line.PopDue(0.5, [&](int v) { got = v; });
  EXPECT_EQ(got, 1);
  EXPECT_EQ(line.lost(), 0);
}

}  // namespace
}  // namespace hs::cli

#include "client/percentiles.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace hs::cli {
namespace {

// The nearest-rank definition itself: the smallest sample x such that at
// least q * n samples are <= x. Quadratic, for the tests only.
double NearestRankByCounting(const std::vector<double>& samples, double q) {
  const double needed = q * static_cast<double>(samples.size());
  double best = INFINITY;
  for (const double x : samples) {
    const auto at_most =
        std::count_if(samples.begin(), samples.end(), [x](double y) { return y <= x; });
    if (static_cast<double>(at_most) >= needed) best = std::min(best, x);
  }
  return best;
}

// Quantile agrees with the counting definition of the nearest rank on
// random samples of every size from 1 to 300, ties included.
TEST(PercentilesTest, QuantileIsTheNearestRank) {
  std::mt19937 rng(20261124);
  std::uniform_int_distribution<int> value(0, 50);  // small range: many ties
  for (int n = 1; n <= 300; ++n) {
    std::vector<double> samples(n);
    for (double& s : samples) s = value(rng) * 0.25;
    std::vector<double> sorted = samples;
    std::sort(sorted.begin(), sorted.end());
    for (const double q : {0.001, 0.25, 0.5, 0.9, 0.99, 0.999, 1.0}) {
      SCOPED_TRACE(::testing::Message() << "n=" << n << " q=" << q);
      EXPECT_EQ(Quantile(sorted, q), NearestRankByCounting(samples, q));
    }
  }
}

// Summarize sorts its input and reports count, mean, max and the three
// quantiles as Quantile gives them.
TEST(PercentilesTest, SummarizeMatchesItsParts) {
  std::mt19937 rng(7);
  std::exponential_distribution<double> latency(1.0);
  std::vector<double> samples(1234);
  double sum = 0;
  double max = 0;
  for (double& s : samples) {
    s = latency(rng);
    sum += s;
    max = std::max(max, s);
  }
  const Percentiles p = Summarize(samples);
  EXPECT_TRUE(std::is_sorted(samples.begin(), samples.end()));
  EXPECT_EQ(p.count, 1234);
  // Summation order differs from the loop above by a few roundings.
  EXPECT_NEAR(p.mean, sum / 1234, 1e-12 * sum);
  EXPECT_EQ(p.max, max);
  EXPECT_EQ(p.p50, Quantile(samples, 0.5));
  EXPECT_EQ(p.p99, Quantile(samples, 0.99));
  EXPECT_EQ(p.p999, Quantile(samples, 0.999));
  EXPECT_LE(p.p50, p.p99);
  EXPECT_LE(p.p99, p.p999);
  EXPECT_LE(p.p999, p.max);
}

// An empty sample gives all zeros rather than reading past the end.
TEST(PercentilesTest, EmptySampleIsAllZero) {
  std::vector<double> none;
  const Percentiles p = Summarize(none);
  EXPECT_EQ(p.count, 0);
  EXPECT_EQ(p.mean, 0);
  EXPECT_EQ(p.p50, 0);
  EXPECT_EQ(p.p99, 0);
  EXPECT_EQ(p.p999, 0);
  EXPECT_EQ(p.max, 0);
}

}  // namespace
}  // namespace hs::cli

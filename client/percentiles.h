#pragma once
// Order statistics of a sample (latencies, step times) from a sorted
// vector: exact nearest-rank percentiles, no histogram.

#include <cstdint>
#include <vector>

namespace hs::cli {

/// Nearest-rank order statistics of a sample; all zero when it is empty.
struct Percentiles {
  int64_t count = 0;
  double mean = 0;
  double p50 = 0;
  double p99 = 0;
  double p999 = 0;
  double max = 0;
};

/// The statistics of `samples` (sorted in place).
Percentiles Summarize(std::vector<double>& samples);

/// The nearest-rank `q` quantile (0 < q <= 1) of sorted, non-empty `sorted`.
double Quantile(const std::vector<double>& sorted, double q);

}  // namespace hs::cli

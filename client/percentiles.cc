#include "client/percentiles.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace hs::cli {

double Quantile(const std::vector<double>& sorted, double q) {
  const auto n = static_cast<double>(sorted.size());
  const auto rank = static_cast<size_t>(std::max(1.0, std::ceil(q * n)));
  return sorted[std::min(rank, sorted.size()) - 1];
}

Percentiles Summarize(std::vector<double>& samples) {
  Percentiles p;
  if (samples.empty()) return p;
  std::sort(samples.begin(), samples.end());
  p.count = static_cast<int64_t>(samples.size());
  p.mean = std::accumulate(samples.begin(), samples.end(), 0.0) / static_cast<double>(p.count);
  p.p50 = Quantile(samples, 0.5);
  p.p99 = Quantile(samples, 0.99);
  p.p999 = Quantile(samples, 0.999);
  p.max = samples.back();
  return p;
}

}  // namespace hs::cli

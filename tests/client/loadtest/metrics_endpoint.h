#pragma once
// A Prometheus /metrics endpoint on a free 127.0.0.1 port for the load
// test's tests (prometheus-cpp), with one counter of CPU seconds as a
// server's process collector exports it; closed when it goes.

#include <memory>
#include <string>

namespace prometheus {
class Counter;
class Exposer;
class Registry;
}  // namespace prometheus

namespace hs::testing {

class MetricsEndpoint {
 public:
  /// Serves process_cpu_seconds_total = `cpu_seconds`.
  explicit MetricsEndpoint(double cpu_seconds);
  ~MetricsEndpoint();

  /// "http://127.0.0.1:PORT/metrics".
  std::string url() const;
  /// Adds to the counter.
  void AddCpuSeconds(double seconds);

 private:
  std::shared_ptr<prometheus::Registry> registry_;
  prometheus::Counter* cpu_;
  std::unique_ptr<prometheus::Exposer> exposer_;
};

}  // namespace hs::testing

#include "tests/client/loadtest/metrics_endpoint.h"

#include <prometheus/counter.h>
#include <prometheus/exposer.h>
#include <prometheus/registry.h>

namespace hs::testing {

MetricsEndpoint::MetricsEndpoint(double cpu_seconds)
    : registry_(std::make_shared<prometheus::Registry>()) {
  cpu_ = &prometheus::BuildCounter()
              .Name("process_cpu_seconds_total")
              .Help("Total user and system CPU time spent in seconds.")
              .Register(*registry_)
              .Add({});
  cpu_->Increment(cpu_seconds);
  exposer_ = std::make_unique<prometheus::Exposer>("127.0.0.1:0");
  exposer_->RegisterCollectable(registry_);
}

MetricsEndpoint::~MetricsEndpoint() = default;

std::string MetricsEndpoint::url() const {
  return "http://127.0.0.1:" + std::to_string(exposer_->GetListeningPorts().front()) + "/metrics";
}

void MetricsEndpoint::AddCpuSeconds(double seconds) { cpu_->Increment(seconds); }

}  // namespace hs::testing

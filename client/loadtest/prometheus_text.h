#pragma once
// Reading one metric from a Prometheus text exposition (format 0.0.4): the
// server's process_cpu_seconds_total for `hapticctl loadtest`.

#include <string_view>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"

namespace hs::cli {

/// The value of metric `name` in `text`: its sample lines ("name value",
/// "name{label=\"v\",...} value", either with a timestamp after) summed
/// over their label sets. Comment and blank lines are passed over, as are
/// other metrics, those whose name only begins with `name` included.
/// NOT_FOUND naming it when it has no sample; INVALID_ARGUMENT quoting the
/// line when one of its samples does not parse.
absl::StatusOr<double> PrometheusValue(absl::string_view text, absl::string_view name);

}  // namespace hs::cli

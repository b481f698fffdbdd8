#include "client/loadtest/prometheus_text.h"

#include "absl/strings/ascii.h"
#include "absl/strings/match.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"

namespace hs::cli {
namespace {

// Where the label set that opens `rest` ends (past its '}'), label values
// being quoted strings that may hold '}' and escaped quotes; npos when it
// does not close.
size_t PastLabels(absl::string_view rest) {
  bool quoted = false;
  for (size_t i = 1; i < rest.size(); ++i) {
    if (quoted && rest[i] == '\\') {
      ++i;
    } else if (rest[i] == '"') {
      quoted = !quoted;
    } else if (!quoted && rest[i] == '}') {
      return i + 1;
    }
  }
  return absl::string_view::npos;
}

}  // namespace

absl::StatusOr<double> PrometheusValue(absl::string_view text, absl::string_view name) {
  double sum = 0;
  bool found = false;
  for (absl::string_view line : absl::StrSplit(text, '\n')) {
    line = absl::StripAsciiWhitespace(line);
    if (!absl::StartsWith(line, name)) continue;
    absl::string_view rest = line.substr(name.size());
    if (rest.empty() || (rest[0] != '{' && rest[0] != ' ' && rest[0] != '\t')) continue;
    const absl::Status bad =
        absl::InvalidArgumentError(absl::StrCat("metrics: cannot read the line '", line, "'"));
    if (rest[0] == '{') {
      const size_t end = PastLabels(rest);
      if (end == absl::string_view::npos) return bad;
      rest.remove_prefix(end);
    }
    const std::vector<absl::string_view> fields =
        absl::StrSplit(rest, absl::ByAnyChar(" \t"), absl::SkipEmpty());
    double value = 0;
    // A value, and maybe a timestamp (milliseconds, a whole number).
    int64_t timestamp_ms = 0;
    if (fields.empty() || fields.size() > 2 || !absl::SimpleAtod(fields[0], &value) ||
        (fields.size() == 2 && !absl::SimpleAtoi(fields[1], &timestamp_ms))) {
      return bad;
    }
    sum += value;
    found = true;
  }
  if (!found) return absl::NotFoundError(absl::StrCat("metrics: no ", name));
  return sum;
}

}  // namespace hs::cli

#pragma once
// The text form of a command's JSON summary: one "key: value" line per
// field, nested objects flattened with dots.

#include <ostream>
#include <string>

#include <nlohmann/json.hpp>

namespace hs::cli {

/// Prints `j` to `out`, each key after `prefix`.
void PrintJsonAsText(const nlohmann::ordered_json& j, const std::string& prefix, std::ostream& out);

}  // namespace hs::cli

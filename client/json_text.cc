#include "client/json_text.h"

namespace hs::cli {

void PrintJsonAsText(const nlohmann::ordered_json& j, const std::string& prefix,
                     std::ostream& out) {
  for (const auto& [key, value] : j.items()) {
    if (value.is_object()) {
      PrintJsonAsText(value, prefix + key + ".", out);
    } else if (value.is_array() && !value.empty() && value.front().is_object()) {
      for (size_t i = 0; i < value.size(); ++i) {
        PrintJsonAsText(value[i], prefix + key + "[" + std::to_string(i) + "].", out);
      }
    } else {
      out << prefix << key << ": " << (value.is_string() ? value.get<std::string>() : value.dump())
          << "\n";
    }
  }
}

}  // namespace hs::cli

#include "common/api/names.h"

#include "absl/strings/str_cat.h"

namespace hs {

absl::Status ValidateName(absl::string_view name) {
  if (name.empty()) return absl::InvalidArgumentError("name: empty");
  if (name.size() > kMaxNameLength) {
    return absl::InvalidArgumentError(
        absl::StrCat("name: ", name.size(), " characters; at most ", kMaxNameLength));
  }
  for (char c : name) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == ' ' || c == '_' || c == '.' || c == '-';
    if (!ok) return absl::InvalidArgumentError("name: only letters, digits, space, _ . - allowed");
  }
  if (name.front() == ' ' || name.back() == ' ') {
    return absl::InvalidArgumentError("name: starts or ends with a space");
  }
  return absl::OkStatus();
}

}  // namespace hs

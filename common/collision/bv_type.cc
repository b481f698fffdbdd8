#include "common/collision/bv_type.h"

#include <array>
#include <string>
#include <utility>

#include "absl/strings/str_cat.h"

namespace hs {
namespace {

constexpr std::array<std::pair<BvType, std::string_view>, 5> kNames = {{
    {BvType::kObbRss, "obbrss"},
    {BvType::kObb, "obb"},
    {BvType::kRss, "rss"},
    {BvType::kKios, "kios"},
    {BvType::kAabb, "aabb"},
}};

}  // namespace

std::string_view BvTypeName(BvType type) {
  for (const auto& [t, name] : kNames) {
    if (t == type) return name;
  }
  return "unknown";
}

absl::StatusOr<BvType> ParseBvType(std::string_view name) {
  for (const auto& [t, n] : kNames) {
    if (n == name) return t;
  }
  return absl::InvalidArgumentError(absl::StrCat("unknown bounding volume '", std::string(name),
                                                 "' (obbrss, obb, rss, kios, aabb)"));
}

}  // namespace hs

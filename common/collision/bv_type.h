#pragma once
// The bounding volume of a collision model's hierarchy. The choice trades
// how tightly the volumes cull against how long they take to build and test.

#include <string_view>

#include "absl/status/statusor.h"

namespace hs {

enum class BvType {
  kObbRss,  ///< OBB for culling, RSS for distance: FCL's best all-rounder (default).
  kObb,     ///< Oriented boxes, as RAPID used.
  kRss,     ///< Rectangle swept spheres.
  kKios,    ///< k-IOS: intersections of spheres.
  kAabb,    ///< Axis-aligned boxes in the object frame: quickest to build, loosest.
};

/// "obbrss", "obb", "rss", "kios" or "aabb".
std::string_view BvTypeName(BvType type);
/// The inverse of BvTypeName; INVALID_ARGUMENT for any other text.
absl::StatusOr<BvType> ParseBvType(std::string_view name);

}  // namespace hs

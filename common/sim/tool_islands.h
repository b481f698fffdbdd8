#pragma once
// Which tools may meet in a step: tools whose reach boxes (every pose their
// proxies can take this step) overlap, directly or through others, form
// one island. Islands are stepped apart, in parallel; the tools of one
// island one after the other, in tool order.

#include <span>
#include <vector>

#include "common/core/types.h"

namespace hs {

class ToolIslands {
 public:
  /// Groups `boxes` (one per tool, world frame) into islands. Keeps its
  /// storage: once it has grouped as many boxes, it allocates nothing.
  void Group(const std::vector<AlignedBox3d>& boxes);

  /// The number of islands, ordered by their first box.
  int size() const { return static_cast<int>(starts_.size()) - 1; }
  /// Island `k`'s box indices, ascending.
  std::span<const int> island(int k) const {
    return std::span<const int>(members_).subspan(starts_[k], starts_[k + 1] - starts_[k]);
  }

 private:
  std::vector<int> parent_;     // union-find over the boxes
  std::vector<int> island_of_;  // per box
  std::vector<int> members_;    // the boxes, island after island
  std::vector<int> starts_;     // where each island starts in members_, and the end
};

}  // namespace hs

#include "common/sim/tool_islands.h"

#include <algorithm>
#include <numeric>

namespace hs {
namespace {

// The root of `i`'s set, halving the path on the way.
int Root(std::vector<int>& parent, int i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];
    i = parent[i];
  }
  return i;
}

}  // namespace

void ToolIslands::Group(const std::vector<AlignedBox3d>& boxes) {
  // A scene has a few tools: every pair is tested, and a union-find joins
  // them. The smaller root wins, so an island's root is its first box.
  const int n = static_cast<int>(boxes.size());
  parent_.resize(n);
  std::iota(parent_.begin(), parent_.end(), 0);
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      if (!boxes[i].intersects(boxes[j])) continue;
      const int a = Root(parent_, i), b = Root(parent_, j);
      if (a != b) parent_[std::max(a, b)] = std::min(a, b);
    }
  }
  // Islands numbered by first box; then the boxes counted into place.
  island_of_.assign(n, -1);
  int count = 0;
  for (int i = 0; i < n; ++i) {
    const int root = Root(parent_, i);
    island_of_[i] = root == i ? count++ : island_of_[root];
  }
  starts_.assign(count + 1, 0);
  for (int i = 0; i < n; ++i) ++starts_[island_of_[i] + 1];
  std::partial_sum(starts_.begin(), starts_.end(), starts_.begin());
  members_.resize(n);
  std::vector<int>& next = parent_;  // no longer needed as a union-find
  next.assign(starts_.begin(), starts_.end() - 1);
  for (int i = 0; i < n; ++i) members_[next[island_of_[i]]++] = i;
}

}  // namespace hs

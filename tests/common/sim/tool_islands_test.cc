#include "common/sim/tool_islands.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace hs {
namespace {

AlignedBox3d Box(double x0, double x1) { return {Vector3d(x0, 0, 0), Vector3d(x1, 1, 1)}; }

std::vector<std::vector<int>> Islands(const ToolIslands& islands) {
  std::vector<std::vector<int>> out;
  for (int k = 0; k < islands.size(); ++k) {
    out.emplace_back(islands.island(k).begin(), islands.island(k).end());
  }
  return out;
}

// Boxes 0 and 3 overlap, 3 and 1 overlap (a chain: one island), 2 and 4
// are alone, 4 touching none by a hair.
TEST(ToolIslandsTest, ChainsJoinAndOthersStandAlone) {
  ToolIslands islands;
  islands.Group({Box(0, 1), Box(1.5, 2.5), Box(10, 11), Box(0.9, 1.6), Box(2.6, 3)});
  EXPECT_EQ(Islands(islands), (std::vector<std::vector<int>>{{0, 1, 3}, {2}, {4}}));
}

// The grouping is the same brute force gives: on random boxes, two boxes
// share an island exactly when a path of overlapping boxes links them.
TEST(ToolIslandsTest, MatchesTheReachabilityOfBruteForce) {
  std::mt19937 random(7);
  std::uniform_int_distribution<int> tenths(0, 99);
  ToolIslands islands;
  for (int round = 0; round < 50; ++round) {
    std::vector<AlignedBox3d> boxes;
    const int n = 1 + round % 9;
    for (int i = 0; i < n; ++i) {
      const double x = tenths(random) / 10.0;
      boxes.push_back(Box(x, x + 1 + tenths(random) % 10 / 10.0));
    }
    islands.Group(boxes);
    // Reachability by repeated relaxation.
    std::vector<std::vector<bool>> linked(n, std::vector<bool>(n, false));
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) linked[i][j] = i == j || boxes[i].intersects(boxes[j]);
    }
    for (int k = 0; k < n; ++k) {
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) linked[i][j] = linked[i][j] || (linked[i][k] && linked[k][j]);
      }
    }
    std::vector<int> island_of(n, -1);
    int previous_first = -1;
    for (int k = 0; k < islands.size(); ++k) {
      const auto members = islands.island(k);
      ASSERT_FALSE(members.empty());
      EXPECT_GT(members.front(), previous_first);  // ordered by first box
      previous_first = members.front();
      for (size_t m = 0; m < members.size(); ++m) {
        if (m > 0) {
          EXPECT_LT(members[m - 1], members[m]);
        }
        island_of[members[m]] = k;
      }
    }
    for (int i = 0; i < n; ++i) {
      ASSERT_GE(island_of[i], 0);
      for (int j = 0; j < n; ++j) EXPECT_EQ(island_of[i] == island_of[j], linked[i][j]);
    }
  }
}

TEST(ToolIslandsTest, NoToolsNoIslands) {
  ToolIslands islands;
  islands.Group({});
  EXPECT_EQ(islands.size(), 0);
}

}  // namespace
}  // namespace hs

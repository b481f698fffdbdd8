// Tool pairs' clashes counted step by step (tool_clashes.h), against a
// hand-written sequence of tool contacts.
#include "common/sim/tool_clashes.h"

#include <gtest/gtest.h>

#include <initializer_list>
#include <utility>
#include <vector>

namespace hs {
namespace {

constexpr double kStepS = 1e-3;
constexpr ObjectId kFixedObject = 5;

// Tools 0, 1 and 2, each touching the objects listed for it.
std::vector<ToolFrame> Touching(std::initializer_list<std::pair<ObjectId, ObjectId>> contacts) {
  std::vector<ToolFrame> tools(3);
  for (int t = 0; t < 3; ++t) tools[t].tool = t;
  for (const auto& [tool, object] : contacts) {
    PairContact pair;
    pair.object = object;
    pair.contact.colliding = true;
    tools[tool].contacts.push_back(pair);
  }
  return tools;
}

void ExpectClash(const ToolClash& clash, ObjectId a, ObjectId b, int64_t count, int steps,
                 bool touching, bool began) {
  EXPECT_EQ(clash.tool_a, a);
  EXPECT_EQ(clash.tool_b, b);
  EXPECT_EQ(clash.count, count);
  EXPECT_DOUBLE_EQ(clash.seconds, steps * kStepS);
  EXPECT_EQ(clash.touching, touching);
  EXPECT_EQ(clash.began, began);
}

TEST(ToolClashesTest, CountsOnsetsAndTimeOfEveryPair) {
  std::vector<ToolClash> clashes;
  CountClashes(Touching({}), kStepS, clashes);
  EXPECT_TRUE(clashes.empty());

  // 0 meets 1: one clash, one step long.
  CountClashes(Touching({{0, 1}, {1, 0}}), kStepS, clashes);
  ASSERT_EQ(clashes.size(), 1u);
  ExpectClash(clashes[0], 0, 1, 1, 1, true, true);

  // Only 1's contacts hold 0: still the same clash, going on.
  CountClashes(Touching({{1, 0}}), kStepS, clashes);
  ASSERT_EQ(clashes.size(), 1u);
  ExpectClash(clashes[0], 0, 1, 1, 2, true, false);

  // 0 touches a fixed object only: the clash is over, its time kept.
  CountClashes(Touching({{0, kFixedObject}}), kStepS, clashes);
  ASSERT_EQ(clashes.size(), 1u);
  ExpectClash(clashes[0], 0, 1, 1, 2, false, false);

  // 0 meets 1 again, and 2 meets 1: a second clash of (0, 1), a first of (1, 2).
  CountClashes(Touching({{0, 1}, {2, 1}}), kStepS, clashes);
  ASSERT_EQ(clashes.size(), 2u);
  ExpectClash(clashes[0], 0, 1, 2, 3, true, true);
  ExpectClash(clashes[1], 1, 2, 1, 1, true, true);

  // 2 meets 0: its entry goes between the others, by pair.
  CountClashes(Touching({{2, 0}, {2, 1}}), kStepS, clashes);
  ASSERT_EQ(clashes.size(), 3u);
  ExpectClash(clashes[0], 0, 1, 2, 3, false, false);
  ExpectClash(clashes[1], 0, 2, 1, 1, true, true);
  ExpectClash(clashes[2], 1, 2, 1, 2, true, false);

  // No contacts listed (no collision stage), but 1's proxy rests on 0's:
  // (0, 1) clashes a third time.
  std::vector<ToolFrame> proxies = Touching({});
  proxies[1].touched_tool = 0;
  CountClashes(proxies, kStepS, clashes);
  ExpectClash(clashes[0], 0, 1, 3, 4, true, true);
  ExpectClash(clashes[1], 0, 2, 1, 1, false, false);
}

}  // namespace
}  // namespace hs

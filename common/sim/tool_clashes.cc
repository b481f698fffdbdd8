#include "common/sim/tool_clashes.h"

#include <algorithm>
#include <utility>

namespace hs {
namespace {

bool IsTool(const std::vector<ToolFrame>& tools, ObjectId id) {
  return std::any_of(tools.begin(), tools.end(), [&](const ToolFrame& t) { return t.tool == id; });
}

// The entry of pair (a, b), a < b, made when there is none.
ToolClash& Entry(std::vector<ToolClash>& clashes, ObjectId a, ObjectId b) {
  const auto at =
      std::lower_bound(clashes.begin(), clashes.end(), std::pair(a, b),
                       [](const ToolClash& c, const std::pair<ObjectId, ObjectId>& key) {
                         return std::pair(c.tool_a, c.tool_b) < key;
                       });
  if (at != clashes.end() && at->tool_a == a && at->tool_b == b) return *at;
  return *clashes.insert(at, ToolClash{.tool_a = a, .tool_b = b});
}

}  // namespace

void CountClashes(const std::vector<ToolFrame>& tools, double step_s,
                  std::vector<ToolClash>& clashes) {
  // Whether each pair touched at the last step, then cleared for this one.
  for (ToolClash& clash : clashes) {
    clash.began = clash.touching;  // for now: touched before
    clash.touching = false;
  }
  auto touch = [&](ObjectId a, ObjectId b) {
    Entry(clashes, std::min(a, b), std::max(a, b)).touching = true;
  };
  for (const ToolFrame& tool : tools) {
    for (const PairContact& pair : tool.contacts) {
      if (IsTool(tools, pair.object)) touch(tool.tool, pair.object);
    }
    if (tool.touched_tool >= 0) touch(tool.tool, tool.touched_tool);
  }
  for (ToolClash& clash : clashes) {
    const bool touched_before = clash.began;
    clash.began = clash.touching && !touched_before;
    if (clash.began) ++clash.count;
    if (clash.touching) clash.seconds += step_s;
  }
}

}  // namespace hs

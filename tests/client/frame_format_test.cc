// A frame as one line of text names each tool's holder and the tool pairs
// touching now.
#include "client/frame_format.h"

#include <gtest/gtest.h>

#include <sstream>
#include <utility>

namespace hs::cli {
namespace {

TEST(FrameFormatTest, NamesHoldersAndClashes) {
  haptics::v1::Frame frame;
  frame.set_step(7);
  frame.add_tools()->set_tool("left");
  frame.mutable_tools(0)->set_holder("alice");
  frame.add_tools()->set_tool("right");
  haptics::v1::ToolClash* now = frame.add_clashes();
  now->set_tool_a("left");
  now->set_tool_b("right");
  now->set_touching(true);
  haptics::v1::ToolClash* before = frame.add_clashes();
  before->set_tool_a("left");
  before->set_tool_b("scalpel");
  std::ostringstream out;
  PrintFrame(frame, /*json=*/false, out);
  const std::string line = out.str();
  EXPECT_NE(line.find("left (held by alice): 0 contact(s)"), std::string::npos) << line;
  EXPECT_NE(line.find("right: 0 contact(s)"), std::string::npos) << line;
  EXPECT_NE(line.find("clash left-right"), std::string::npos) << line;
  EXPECT_EQ(line.find("scalpel"), std::string::npos) << line;
}

// The frames the stream dropped are counted since it began, and the line
// says so; a stream that dropped none says nothing.
TEST(FrameFormatTest, SaysDroppedFramesAreCountedSoFar) {
  haptics::v1::Frame frame;
  frame.set_step(9);
  std::ostringstream none;
  PrintFrame(frame, /*json=*/false, none);
  EXPECT_EQ(none.str().find("dropped"), std::string::npos) << none.str();
  frame.set_dropped_frames(3);
  std::ostringstream some;
  PrintFrame(frame, /*json=*/false, some);
  EXPECT_NE(some.str().find("(3 frames dropped so far)"), std::string::npos) << some.str();
}

// The clash totals sum every pair, touching now or not.
TEST(FrameFormatTest, SumsClashesOverPairs) {
  haptics::v1::Frame frame;
  for (const auto& [count, seconds] : {std::pair{2, 0.25}, std::pair{3, 0.5}}) {
    haptics::v1::ToolClash* clash = frame.add_clashes();
    clash->set_count(count);
    clash->set_duration_s(seconds);
  }
  const ClashTotals totals = SumClashes(frame);
  EXPECT_EQ(totals.count, 5);
  EXPECT_EQ(totals.seconds, 0.75);
}

}  // namespace
}  // namespace hs::cli

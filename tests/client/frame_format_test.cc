// A frame as one line of text names each tool's holder and the tool pairs
// touching now.
#include "client/frame_format.h"

#include <gtest/gtest.h>

#include <sstream>

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

}  // namespace
}  // namespace hs::cli

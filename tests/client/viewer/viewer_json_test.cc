// The page's frame JSON names each tool's holder: this bridge's pages by
// their number, every other tool as the server's frame names it.
#include "client/viewer/viewer_json.h"

#include <gtest/gtest.h>

namespace hs::cli {
namespace {

TEST(ViewerJsonTest, HoldersFromPagesThenFromTheFrame) {
  haptics::v1::Frame frame;
  frame.add_tools()->set_tool("probe");
  frame.mutable_tools(0)->set_holder("peer:10.0.0.7");  // this bridge's page drives it
  frame.add_tools()->set_tool("stylus");
  frame.mutable_tools(1)->set_holder("dr.lee");
  frame.add_tools()->set_tool("free");
  const nlohmann::json json =
      FrameJson(frame, FrameExtras{.page_holders = {{"probe", "viewer page 2"}}});
  ASSERT_EQ(json["tools"].size(), 3u);
  EXPECT_EQ(json["tools"][0]["holder"], "viewer page 2");
  EXPECT_EQ(json["tools"][1]["holder"], "dr.lee");
  EXPECT_EQ(json["tools"][2]["holder"], "");
}

}  // namespace
}  // namespace hs::cli

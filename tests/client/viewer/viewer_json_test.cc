// The page's frame JSON names each tool's holder: this bridge's pages by
// their number, every other tool as the server's frame names it; and it
// carries the frame's free bodies as the frame has them.
#include "client/viewer/viewer_json.h"

#include <gtest/gtest.h>

namespace hs::cli {
namespace {

// This bridge's pages are named by number, other holders as the frame has them.
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

// Each body of the frame goes to the page with its pose (position, then
// the quaternion w first) and who touches and holds it; a frame without
// bodies gives an empty list.
TEST(ViewerJsonTest, BodiesAsTheFrameHasThem) {
  haptics::v1::Frame frame;
  EXPECT_EQ(FrameJson(frame, {})["bodies"], nlohmann::json::array());
  haptics::v1::BodyState* body = frame.add_bodies();
  body->set_name("pebble");
  body->mutable_pose()->mutable_position_m()->set_z(0.02);
  body->mutable_pose()->mutable_orientation()->set_w(1);
  body->add_touching_tools("left");
  body->add_touching_tools("right");
  body->set_held(true);
  const nlohmann::json json = FrameJson(frame, {});
  ASSERT_EQ(json["bodies"].size(), 1u);
  const nlohmann::json& pebble = json["bodies"][0];
  EXPECT_EQ(pebble["name"], "pebble");
  EXPECT_EQ(pebble["pose"]["p"], nlohmann::json::array({0.0, 0.0, 0.02}));
  EXPECT_EQ(pebble["pose"]["q"], nlohmann::json::array({1.0, 0.0, 0.0, 0.0}));
  EXPECT_EQ(pebble["touching_tools"], nlohmann::json::array({"left", "right"}));
  EXPECT_EQ(pebble["held"], true);
}

}  // namespace
}  // namespace hs::cli

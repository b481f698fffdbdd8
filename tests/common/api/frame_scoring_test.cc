// A server's frame as the scorer reads it: the tool's pose, force and
// contacts, and the pose's device time only from the tool's own device
// stream, after its first pose, when the device stamps it.

#include "common/api/frame_scoring.h"

#include <gtest/gtest.h>

namespace hs {
namespace {

namespace pb = haptics::v1;

// A frame at 0.25 s with tool "probe" at (1, 2, 3) pushed with (0, 0, 4)
// N against "organ" at (1, 2, 2.9), and another tool; the last pose
// applied to the stream's device is number `sequence`, stamped `device_ns`.
pb::Frame Frame(uint64_t sequence, int64_t device_ns) {
  pb::Frame frame;
  frame.set_time_s(0.25);
  frame.set_last_pose_sequence(sequence);
  frame.set_last_pose_device_time_ns(device_ns);
  frame.add_tools()->set_tool("other");
  pb::ToolState* tool = frame.add_tools();
  tool->set_tool("probe");
  tool->mutable_device_pose()->mutable_position_m()->set_x(1);
  tool->mutable_device_pose()->mutable_position_m()->set_y(2);
  tool->mutable_device_pose()->mutable_position_m()->set_z(3);
  tool->mutable_force_w_n()->set_z(4);
  pb::Contact* contact = tool->add_contacts();
  contact->set_object("organ");
  pb::Vector3* point = contact->add_points()->mutable_p_wc_m();
  point->set_x(1);
  point->set_y(2);
  point->set_z(2.9);
  return frame;
}

// The tool's part is read whatever the stream.
TEST(FrameScoringTest, ReadsTheToolsPart) {
  const ScoringFrame f = ScoringFrameFromProto(Frame(0, 0), "probe", FrameStream::kWatch);
  EXPECT_EQ(f.time_s, 0.25);
  EXPECT_EQ(f.p_WD, Vector3d(1, 2, 3));
  EXPECT_EQ(f.force_W, Vector3d(0, 0, 4));
  ASSERT_EQ(f.contacts.size(), 1u);
  EXPECT_EQ(f.contacts[0].object, "organ");
  ASSERT_EQ(f.contacts[0].points_W.size(), 1u);
  EXPECT_EQ(f.contacts[0].points_W[0], Vector3d(1, 2, 2.9));
}

// The device time (2.5 s) times the pose on the tool's own device stream
// only; not before its first pose, nor when the device does not stamp.
TEST(FrameScoringTest, PoseTimeFromTheToolsOwnStream) {
  EXPECT_EQ(ScoringFrameFromProto(Frame(3, 2'500'000'000), "probe", FrameStream::kToolsDevice)
                .pose_time_s,
            2.5);
  EXPECT_FALSE(ScoringFrameFromProto(Frame(3, 2'500'000'000), "probe", FrameStream::kWatch)
                   .pose_time_s.has_value());
  EXPECT_FALSE(ScoringFrameFromProto(Frame(0, 2'500'000'000), "probe", FrameStream::kToolsDevice)
                   .pose_time_s.has_value());
  EXPECT_FALSE(ScoringFrameFromProto(Frame(3, 0), "probe", FrameStream::kToolsDevice)
                   .pose_time_s.has_value());
}

}  // namespace
}  // namespace hs

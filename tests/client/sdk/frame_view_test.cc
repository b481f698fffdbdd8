#include "client/sdk/frame_view.h"

#include <gtest/gtest.h>

namespace hs::sdk {
namespace {

namespace pb = haptics::v1;

TEST(FrameViewTest, CopiesEveryPartOfAFrame) {
  // Each field of a frame with every part lands in its plain counterpart.
  pb::Frame frame;
  frame.set_step(42);
  frame.set_time_s(0.042);
  frame.set_dropped_frames(3);
  frame.set_missed_steps(2);
  pb::ToolState* tool = frame.add_tools();
  tool->set_tool("probe");
  tool->set_holder("peer:x");
  tool->mutable_device_pose()->mutable_position_m()->set_z(0.1);
  tool->mutable_device_pose()->mutable_orientation()->set_w(0.6);
  tool->mutable_device_pose()->mutable_orientation()->set_x(0.8);
  tool->mutable_force_w_n()->set_z(2);
  tool->mutable_torque_w_nm()->set_x(-0.5);
  tool->set_force_clamped(true);
  pb::Contact* contact = tool->add_contacts();
  contact->set_object("organ");
  contact->set_penetrating(true);
  contact->set_depth_m(0.005);
  contact->mutable_normal_w()->set_z(1);
  contact->add_points()->mutable_p_wc_m()->set_x(0.1);
  contact->set_time_of_impact(0.25);
  contact->set_has_time_of_impact(true);
  pb::LocalModel* model = tool->mutable_local_model();
  model->set_revision(7);
  model->set_validity_radius_m(0.01);
  model->set_force_clamp_n(10);
  pb::ConstraintPlane* plane = model->add_planes();
  plane->set_object("organ");
  plane->mutable_normal_w()->set_z(1);
  plane->set_gap_m(0.001);
  plane->set_separating(true);
  plane->mutable_material()->set_stiffness_n_per_m(400);

  const haptics::Frame out = FrameFromProto(frame);
  EXPECT_EQ(out.step, 42);
  EXPECT_EQ(out.time_s, 0.042);
  EXPECT_EQ(out.dropped_frames, 3u);
  EXPECT_EQ(out.missed_steps, 2);
  ASSERT_EQ(out.tools.size(), 1u);
  const haptics::ToolFrame& t = out.tools[0];
  EXPECT_EQ(t.tool, "probe");
  EXPECT_EQ(t.holder, "peer:x");
  EXPECT_EQ(t.device_pose.position_m[2], 0.1);
  EXPECT_EQ(t.device_pose.orientation_wxyz[0], 0.6);
  EXPECT_EQ(t.device_pose.orientation_wxyz[1], 0.8);
  // A pose the frame left out is the identity.
  EXPECT_EQ(t.proxy_pose.orientation_wxyz[0], 1);
  EXPECT_EQ(t.force_n[2], 2);
  EXPECT_EQ(t.torque_nm[0], -0.5);
  EXPECT_TRUE(t.force_clamped);
  ASSERT_EQ(t.contacts.size(), 1u);
  EXPECT_EQ(t.contacts[0].object, "organ");
  EXPECT_TRUE(t.contacts[0].penetrating);
  EXPECT_EQ(t.contacts[0].depth_m, 0.005);
  EXPECT_EQ(t.contacts[0].normal_w[2], 1);
  EXPECT_EQ(t.contacts[0].points_w_m, (std::vector<double>{0.1, 0, 0}));
  EXPECT_EQ(t.contacts[0].time_of_impact, 0.25);
  ASSERT_TRUE(t.has_local_model);
  EXPECT_EQ(t.local_model.revision, 7u);
  EXPECT_EQ(t.local_model.validity_radius_m, 0.01);
  ASSERT_EQ(t.local_model.planes.size(), 1u);
  EXPECT_EQ(t.local_model.planes[0].object, "organ");
  EXPECT_EQ(t.local_model.planes[0].gap_m, 0.001);
  EXPECT_TRUE(t.local_model.planes[0].separating);
  EXPECT_EQ(t.local_model.planes[0].stiffness_n_per_m, 400);
}

TEST(FrameViewTest, PartsLeftOutStayEmpty) {
  // No contacts, no model, no time of impact: empty, false and -1.
  pb::Frame frame;
  frame.add_tools()->add_contacts()->set_object("table");
  const haptics::Frame out = FrameFromProto(frame);
  ASSERT_EQ(out.tools.size(), 1u);
  EXPECT_FALSE(out.tools[0].has_local_model);
  EXPECT_EQ(out.tools[0].contacts[0].time_of_impact, -1);
}

}  // namespace
}  // namespace hs::sdk

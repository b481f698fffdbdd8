#include "common/api/proto_convert.h"

#include <gtest/gtest.h>

#include <cmath>

namespace hs {
namespace {

namespace pb = haptics::v1;

// A pose survives Isometry3d -> proto -> Isometry3d (to rounding), and the
// all-zero quaternion means no rotation.
TEST(ProtoConvertTest, PoseRoundTrip) {
  Isometry3d X = Isometry3d::Identity();
  X.linear() = Eigen::AngleAxisd(0.7, Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  X.translation() = Vector3d(0.1, -0.2, 0.3);
  pb::Pose pose;
  PoseToProto(X, &pose);
  absl::StatusOr<Isometry3d> back = PoseFromProto(pose, "pose");
  ASSERT_TRUE(back.ok()) << back.status();
  EXPECT_TRUE(back->isApprox(X, 1e-12));  // one quaternion round trip

  pb::Pose zero;
  absl::StatusOr<Isometry3d> identity = PoseFromProto(zero, "pose");
  ASSERT_TRUE(identity.ok());
  EXPECT_TRUE(identity->isApprox(Isometry3d::Identity(), 0.0));
}

// Non-finite numbers, huge coordinates and non-unit quaternions are
// INVALID_ARGUMENT naming the field.
TEST(ProtoConvertTest, RejectsBadNumbers) {
  pb::Pose pose;
  pose.mutable_position_m()->set_x(std::nan(""));
  EXPECT_EQ(PoseFromProto(pose, "p").status().code(), absl::StatusCode::kInvalidArgument);
  pose.mutable_position_m()->set_x(1e300);
  EXPECT_EQ(PoseFromProto(pose, "p").status().code(), absl::StatusCode::kInvalidArgument);
  pose.mutable_position_m()->set_x(0);
  pose.mutable_orientation()->set_w(0.5);
  const absl::Status s = PoseFromProto(pose, "p").status();
  EXPECT_EQ(s.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(s.message().find("p.orientation"), std::string::npos);
}

// Effects map one to one, in order; unspecified and unknown values are
// rejected, and an empty list takes the default.
TEST(ProtoConvertTest, Effects) {
  google::protobuf::RepeatedField<int> effects;
  EXPECT_EQ(*EffectsFromProto(effects, EffectSet::All(), "e"), EffectSet::All());
  effects.Add(pb::EFFECT_FORCE);
  EXPECT_EQ(*EffectsFromProto(effects, EffectSet::All(), "e"), EffectSet{Effect::kForce});
  EXPECT_EQ(EffectToProto(Effect::kForce), pb::EFFECT_FORCE);
  effects.Add(0);
  EXPECT_FALSE(EffectsFromProto(effects, EffectSet::All(), "e").ok());
}

// Clashes go out by tool name, with the contacts part only.
TEST(ProtoConvertTest, ClashesByNameWithContacts) {
  StepFrame frame;
  frame.clashes.push_back(
      {.tool_a = 1, .tool_b = 2, .count = 3, .seconds = 0.25, .touching = true, .began = false});
  const std::vector<std::string> names = {"box", "left", "right"};
  pb::Frame out;
  StepFrameToProto(frame, names, FrameParts{}, &out);
  ASSERT_EQ(out.clashes_size(), 1);
  EXPECT_EQ(out.clashes(0).tool_a(), "left");
  EXPECT_EQ(out.clashes(0).tool_b(), "right");
  EXPECT_EQ(out.clashes(0).count(), 3);
  EXPECT_EQ(out.clashes(0).duration_s(), 0.25);
  EXPECT_TRUE(out.clashes(0).touching());
  StepFrameToProto(frame, names, FrameParts{.contacts = false}, &out);
  EXPECT_EQ(out.clashes_size(), 0);
}

// Every tool goes out unless one is asked for: then that one alone, and
// none for an id no tool has.
TEST(ProtoConvertTest, OnlyTheToolAskedFor) {
  StepFrame frame;
  frame.tools.resize(2);
  frame.tools[0].tool = 1;
  frame.tools[1].tool = 2;
  const std::vector<std::string> names = {"box", "left", "right"};
  pb::Frame out;
  StepFrameToProto(frame, names, FrameParts{}, &out);
  ASSERT_EQ(out.tools_size(), 2);
  StepFrameToProto(frame, names, FrameParts{.only_tool = 2}, &out);
  ASSERT_EQ(out.tools_size(), 1);
  EXPECT_EQ(out.tools(0).tool(), "right");
  StepFrameToProto(frame, names, FrameParts{.only_tool = -1}, &out);
  EXPECT_EQ(out.tools_size(), 0);
}

}  // namespace
}  // namespace hs

#include "common/recording/recorded_step.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "tests/common/random_poses.h"

namespace hs {
namespace {

namespace pb = haptics::v1;

// A frame with one tool pressing on one object, every field set.
StepFrame SomeFrame() {
  StepFrame frame;
  frame.step = 3;
  frame.stages_run = EffectSet::All();
  ToolFrame& tool = frame.tools.emplace_back();
  tool.tool = 1;
  tool.X_WD.translation() = Vector3d(0.1, 0.2, 0.3);
  tool.force_W = Vector3d(0, 0, 2.5);
  PairContact& pair = tool.contacts.emplace_back();
  pair.object = 0;
  pair.contact.colliding = true;
  pair.contact.depth_m = 0.001;
  pair.contact.normal_W = Vector3d::UnitZ();
  return frame;
}

const std::vector<std::string> kNames = {"table", "probe"};

// In full, the frame is kept with its step, time and needs; as a digest,
// only the SHA-256 of that same frame.
TEST(RecordedStepTest, FullAndDigestKeepTheSameFrame) {
  const EffectSet needs{Effect::kCollision, Effect::kForce};
  pb::RecordedFrame full, digest;
  FillRecordedFrame(7, 0.007, SomeFrame(), kNames, needs, pb::FRAME_RECORDING_FULL, &full);
  FillRecordedFrame(7, 0.007, SomeFrame(), kNames, needs, pb::FRAME_RECORDING_DIGEST, &digest);
  EXPECT_EQ(full.step(), 7);
  ASSERT_TRUE(full.has_frame());
  EXPECT_EQ(full.frame().step(), 7);
  EXPECT_EQ(full.frame().time_s(), 0.007);
  EXPECT_EQ(full.needs_size(), 2);
  EXPECT_EQ(digest.step(), 7);
  EXPECT_EQ(digest.needs_size(), 2);
  EXPECT_FALSE(digest.has_frame());
  EXPECT_EQ(digest.sha256(), FrameDigest(full.frame()));
  EXPECT_EQ(digest.sha256().size(), 32u);
}

// Filling writes the frame over whatever the message held.
TEST(RecordedStepTest, FillWritesOver) {
  pb::RecordedFrame out;
  FillRecordedFrame(1, 0.001, SomeFrame(), kNames, EffectSet::All(), pb::FRAME_RECORDING_DIGEST,
                    &out);
  FillRecordedFrame(2, 0.002, StepFrame{}, {}, EffectSet{}, pb::FRAME_RECORDING_FULL, &out);
  EXPECT_EQ(out.step(), 2);
  EXPECT_TRUE(out.has_frame());
  EXPECT_EQ(out.needs_size(), 0);
  EXPECT_EQ(out.frame().tools_size(), 0);
}

// The digest is the same for equal frames and differs when any field does.
TEST(RecordedStepTest, DigestFollowsTheFrame) {
  pb::RecordedFrame a, b;
  FillRecordedFrame(7, 0.007, SomeFrame(), kNames, {}, pb::FRAME_RECORDING_FULL, &a);
  FillRecordedFrame(7, 0.007, SomeFrame(), kNames, {}, pb::FRAME_RECORDING_FULL, &b);
  EXPECT_EQ(FrameDigest(a.frame()), FrameDigest(b.frame()));
  StepFrame pressed = SomeFrame();
  pressed.tools[0].force_W.z() = std::nextafter(2.5, 3.0);
  FillRecordedFrame(7, 0.007, pressed, kNames, {}, pb::FRAME_RECORDING_FULL, &b);
  EXPECT_NE(FrameDigest(a.frame()), FrameDigest(b.frame()));
}

bool SameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Poses go through the proto bit for bit: random ones, and a negative
// zero, a denormal and the largest double.
TEST(RecordedStepTest, ExactPoseRoundTripsBitForBit) {
  std::mt19937 rng(12);
  std::vector<Isometry3d> poses;
  for (int k = 0; k < 100; ++k) poses.push_back(testing_poses::RandomPose(rng, 10));
  Isometry3d odd = Isometry3d::Identity();
  odd.translation() =
      Vector3d(-0.0, std::numeric_limits<double>::denorm_min(), std::numeric_limits<double>::max());
  poses.push_back(odd);
  for (const Isometry3d& X : poses) {
    pb::ExactPose proto;
    ExactPoseToProto(X, &proto);
    const absl::StatusOr<Isometry3d> back = ExactPoseFromProto(proto);
    ASSERT_TRUE(back.ok()) << back.status();
    for (int i = 0; i < 16; ++i) {
      EXPECT_TRUE(SameBits(back->matrix().data()[i], X.matrix().data()[i])) << i;
    }
  }
}

// A rotation without 9 numbers, or any number not finite, is
// INVALID_ARGUMENT.
TEST(RecordedStepTest, BadPosesAreRefused) {
  pb::ExactPose good;
  ExactPoseToProto(Isometry3d::Identity(), &good);
  pb::ExactPose short_rotation = good;
  short_rotation.mutable_rotation_row_major()->RemoveLast();
  EXPECT_EQ(ExactPoseFromProto(short_rotation).status().code(), absl::StatusCode::kInvalidArgument);
  pb::ExactPose nan_rotation = good;
  nan_rotation.set_rotation_row_major(4, std::numeric_limits<double>::quiet_NaN());
  EXPECT_EQ(ExactPoseFromProto(nan_rotation).status().code(), absl::StatusCode::kInvalidArgument);
  pb::ExactPose infinite_translation = good;
  infinite_translation.mutable_translation_m()->set_y(std::numeric_limits<double>::infinity());
  EXPECT_EQ(ExactPoseFromProto(infinite_translation).status().code(),
            absl::StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace hs

#include "common/recording/replay.h"

#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <vector>

#include "tests/common/recording/recorded_run.h"
#include "tests/common/scratch_dir.h"

namespace hs {
namespace {

namespace pb = haptics::v1;
using testing_recording::RecordRun;
using testing_recording::RunOptions;
using testing_recording::WriteRecords;

std::string Write(const std::string& name, const std::vector<pb::Record>& records) {
  return WriteRecords((ScratchDir("replay") / name).string(), records);
}

// The round trip: a run recorded by stepping the scene directly, device
// poses and an edit included, replays to the same frame at every step, in
// full and as digests; on_step sees each step once, at its time.
TEST(ReplayTest, RecordedRunReplaysBitForBit) {
  for (const pb::FrameRecording frames : {pb::FRAME_RECORDING_FULL, pb::FRAME_RECORDING_DIGEST}) {
    SCOPED_TRACE(pb::FrameRecording_Name(frames));
    const std::string file = Write(pb::FrameRecording_Name(frames) + ".hsrec",
                                   RecordRun({.frames = frames, .steps = 12, .edit_after = 6}));
    std::vector<double> times;
    ReplayOptions options;
    options.on_step = [&](double time_s, const StepFrame&, const std::vector<std::string>& names) {
      times.push_back(time_s);
      EXPECT_EQ(names, (std::vector<std::string>{"table", "probe"}));
    };
    const absl::StatusOr<ReplayReport> report = ReplayRecording(file, options);
    ASSERT_TRUE(report.ok()) << report.status();
    EXPECT_EQ(report->steps_compared, 12);
    EXPECT_TRUE(report->all_identical()) << report->first_divergent_field;
    EXPECT_EQ(report->first_divergent_step, 0);
    ASSERT_EQ(report->files.size(), 1u);
    EXPECT_EQ(report->files[0].path, file);
    ASSERT_EQ(times.size(), 12u);
    for (int i = 0; i < 12; ++i) EXPECT_DOUBLE_EQ(times[i], (i + 1) * testing_recording::kStepS);
  }
}

// A frame changed in the file is the first divergence, at its step, and
// named by its field; the later identical frames still count.
TEST(ReplayTest, ChangedFrameIsFoundAtItsStep) {
  std::vector<pb::Record> records = RecordRun({.steps = 10});
  for (pb::Record& record : records) {
    if (record.has_frame() && record.frame().step() == 7) {
      record.mutable_frame()->mutable_frame()->set_time_s(1.5);
    }
  }
  const absl::StatusOr<ReplayReport> report = ReplayRecording(Write("changed.hsrec", records), {});
  ASSERT_TRUE(report.ok()) << report.status();
  EXPECT_EQ(report->first_divergent_step, 7);
  EXPECT_NE(report->first_divergent_field.find("time_s"), std::string::npos)
      << report->first_divergent_field;
  EXPECT_EQ(report->steps_compared, 10);
  EXPECT_EQ(report->identical, 9);
  EXPECT_FALSE(report->all_identical());
}

// A changed digest is a divergence of the "frame digest".
TEST(ReplayTest, ChangedDigestIsADivergence) {
  std::vector<pb::Record> records = RecordRun({.frames = pb::FRAME_RECORDING_DIGEST, .steps = 5});
  records[4].mutable_frame()->set_sha256(std::string(32, 'x'));  // start, (input, frame) x 2
  ASSERT_EQ(records[4].frame().step(), 2);
  const absl::StatusOr<ReplayReport> report = ReplayRecording(Write("digest.hsrec", records), {});
  ASSERT_TRUE(report.ok()) << report.status();
  EXPECT_EQ(report->first_divergent_step, 2);
  EXPECT_EQ(report->first_divergent_field, "frame digest");
}

// Steps the recorder skipped end the replay there, saying so.
TEST(ReplayTest, GapStopsTheReplay) {
  std::vector<pb::Record> records = RecordRun({.steps = 6});
  // After step 3's frame (start, then input and frame per step).
  pb::Record gap;
  gap.mutable_gap()->set_first_step(4);
  gap.mutable_gap()->set_steps(2);
  records.insert(records.begin() + 7, gap);
  const absl::StatusOr<ReplayReport> report = ReplayRecording(Write("gap.hsrec", records), {});
  ASSERT_TRUE(report.ok()) << report.status();
  EXPECT_EQ(report->steps_compared, 3);
  EXPECT_EQ(report->identical, 3);
  EXPECT_NE(report->stopped_early.find("skipped 2 steps from step 4"), std::string::npos)
      << report->stopped_early;
  EXPECT_FALSE(report->all_identical());
}

// Asking for more effects than were recorded changes the frames.
TEST(ReplayTest, ExtraNeedsChangeTheFrames) {
  const std::string file = Write("extra.hsrec", RecordRun({.steps = 4}));
  ReplayOptions options;
  options.extra_needs = EffectSet{Effect::kLocalModel};
  const absl::StatusOr<ReplayReport> report = ReplayRecording(file, options);
  ASSERT_TRUE(report.ok()) << report.status();
  EXPECT_EQ(report->steps_compared, 4);
  EXPECT_LT(report->identical, 4);
}

// A remote device's requests of its local model (a radius, the surface
// alone, a fresh model now and then) are replayed with its poses: the
// replay is bit for bit, and the same records without them diverge (the
// models then carry planes and the scene's radius).
TEST(ReplayTest, LocalModelRequestsReplayWithTheirPoses) {
  const std::vector<pb::Record> records =
      RecordRun({.steps = 12,
                 .remote_device = true,
                 .model = {.validity_radius_m = 0.02, .surface_only = true},
                 .model_stale_at = {5, 9}});
  absl::StatusOr<ReplayReport> report = ReplayRecording(Write("model.hsrec", records), {});
  ASSERT_TRUE(report.ok()) << report.status();
  EXPECT_EQ(report->steps_compared, 12);
  EXPECT_TRUE(report->all_identical()) << report->first_divergent_field;

  std::vector<pb::Record> without = records;
  for (pb::Record& record : without) {
    if (!record.has_input()) continue;
    record.mutable_input()->clear_validity_radius_m();
    record.mutable_input()->clear_surface_only();
    record.mutable_input()->clear_model_stale();
  }
  report = ReplayRecording(Write("model_dropped.hsrec", without), {});
  ASSERT_TRUE(report.ok()) << report.status();
  EXPECT_EQ(report->steps_compared, 12);
  EXPECT_FALSE(report->all_identical());
}

// A radius no device could have sent (non-finite, negative) is
// INVALID_ARGUMENT naming its step.
TEST(ReplayTest, ImpossibleLocalModelRadiusIsRefused) {
  for (const double radius :
       {-0.01, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    std::vector<pb::Record> records = RecordRun({.steps = 3, .remote_device = true});
    for (pb::Record& record : records) {
      if (record.has_input() && record.input().step() == 2) {
        record.mutable_input()->set_validity_radius_m(radius);
      }
    }
    const absl::StatusOr<ReplayReport> report =
        ReplayRecording(Write("bad_radius.hsrec", records), {});
    EXPECT_EQ(report.status().code(), absl::StatusCode::kInvalidArgument) << radius;
    EXPECT_NE(report.status().message().find("step 2"), std::string::npos) << report.status();
  }
}

// A later part of a session, records out of order and a scene that does
// not build are INVALID_ARGUMENT saying which.
TEST(ReplayTest, UnreplayableRecordingsAreRefused) {
  std::vector<pb::Record> later = RecordRun({.steps = 2});
  later[0].mutable_start()->set_part(1);
  absl::StatusOr<ReplayReport> report = ReplayRecording(Write("part1.hsrec", later), {});
  EXPECT_EQ(report.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(report.status().message().find("is part 1"), std::string::npos) << report.status();

  std::vector<pb::Record> swapped = RecordRun({.steps = 3});
  std::swap(swapped[1], swapped[2]);  // step 1's frame before its input
  report = ReplayRecording(Write("swapped.hsrec", swapped), {});
  EXPECT_EQ(report.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(report.status().message().find("out of order"), std::string::npos) << report.status();

  std::vector<pb::Record> lost = RecordRun({.steps = 2});
  pb::SceneSpec& spec = *lost[0].mutable_start()->mutable_spec();
  spec.mutable_objects(0)->mutable_model()->set_uploaded_model_id("gone.obj");
  lost[0].mutable_start()->set_uploaded_models_dir(ScratchDir("replay_no_models").string());
  report = ReplayRecording(Write("lost.hsrec", lost), {});
  EXPECT_EQ(report.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(report.status().message().find("gone.obj"), std::string::npos) << report.status();
}

}  // namespace
}  // namespace hs

#include "common/recording/recording_summary.h"

#include <gtest/gtest.h>

#include <vector>

#include "tests/common/recording/recorded_run.h"
#include "tests/common/scratch_dir.h"

namespace hs {
namespace {

namespace pb = haptics::v1;
using testing_recording::RecordRun;
using testing_recording::WriteRecords;

std::string Write(const std::string& name, const std::vector<pb::Record>& records) {
  return WriteRecords((ScratchDir("recording_summary") / name).string(), records);
}

pb::Record Stream(bool attached, bool device, const std::string& tool) {
  pb::Record record;
  record.mutable_stream()->set_attached(attached);
  record.mutable_stream()->set_device(device);
  record.mutable_stream()->set_tool(tool);
  return record;
}

// A run's figures are the counts of what it recorded: its scene, start,
// step, frames, inputs, edits, streams, gaps and end.
TEST(RecordingSummaryTest, CountsWhatWasRecorded) {
  std::vector<pb::Record> records =
      RecordRun({.frames = pb::FRAME_RECORDING_DIGEST, .steps = 9, .edit_after = 4});
  const pb::Record end = records.back();
  records.pop_back();
  records.push_back(Stream(true, true, "probe"));
  records.push_back(Stream(true, true, "probe"));
  records.push_back(Stream(true, true, "grasper"));
  records.push_back(Stream(false, true, "probe"));  // a detach counts no stream
  records.push_back(Stream(true, false, ""));
  pb::Record gap;
  gap.mutable_gap()->set_first_step(10);
  gap.mutable_gap()->set_steps(5);
  records.push_back(gap);
  gap.mutable_gap()->set_first_step(20);
  gap.mutable_gap()->set_steps(2);
  records.push_back(gap);
  records.push_back(end);
  const absl::StatusOr<RecordingSummary> summary = SummarizeRecording(Write("run.hsrec", records));
  ASSERT_TRUE(summary.ok()) << summary.status();
  EXPECT_EQ(summary->scene, "press");
  EXPECT_EQ(summary->start_unix_ns, testing_recording::kStartUnixNs);
  EXPECT_EQ(summary->step_s, testing_recording::kStepS);
  EXPECT_EQ(summary->frames, "digest");
  EXPECT_EQ(summary->first_step, 1);
  EXPECT_EQ(summary->last_step, 9);
  EXPECT_EQ(summary->steps, 9);
  EXPECT_DOUBLE_EQ(summary->duration_s, 9 * testing_recording::kStepS);
  EXPECT_EQ(summary->inputs, 9);
  EXPECT_EQ(summary->edits, 1);
  EXPECT_EQ(summary->device_streams, 3);
  EXPECT_EQ(summary->device_tools, (std::set<std::string>{"grasper", "probe"}));
  EXPECT_EQ(summary->viewer_streams, 1);
  EXPECT_EQ(summary->gaps, 2);
  EXPECT_EQ(summary->gap_steps, 7);
  EXPECT_TRUE(summary->ended);
  ASSERT_EQ(summary->files.size(), 1u);
}

// A session with no frames and no end (a crash before the first step) has
// zero steps and did not end; frames in full say "full".
TEST(RecordingSummaryTest, EmptySessionThatDidNotEnd) {
  std::vector<pb::Record> records = RecordRun({.steps = 0});
  records.pop_back();  // the end
  const absl::StatusOr<RecordingSummary> summary =
      SummarizeRecording(Write("empty.hsrec", records));
  ASSERT_TRUE(summary.ok()) << summary.status();
  EXPECT_EQ(summary->frames, "full");
  EXPECT_EQ(summary->steps, 0);
  EXPECT_EQ(summary->first_step, 0);
  EXPECT_EQ(summary->last_step, 0);
  EXPECT_EQ(summary->duration_s, 0);
  EXPECT_FALSE(summary->ended);
}

// An end that rolled the session over to a next part is not the session's
// end.
TEST(RecordingSummaryTest, RolledOverEndIsNoEnd) {
  std::vector<pb::Record> records = RecordRun({.steps = 2});
  records.back().mutable_end()->set_rolled_over(true);
  const absl::StatusOr<RecordingSummary> summary =
      SummarizeRecording(Write("rolled.hsrec", records));
  ASSERT_TRUE(summary.ok()) << summary.status();
  EXPECT_FALSE(summary->ended);
}

// A file that is no recording is the reader's error, unchanged.
TEST(RecordingSummaryTest, NotARecordingIsAnError) {
  EXPECT_EQ(SummarizeRecording((ScratchDir("recording_summary_missing") / "none.hsrec").string())
                .status()
                .code(),
            absl::StatusCode::kNotFound);
}

}  // namespace
}  // namespace hs

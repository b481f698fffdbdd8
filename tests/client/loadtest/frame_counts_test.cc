#include "client/loadtest/frame_counts.h"

#include <gtest/gtest.h>

namespace hs::cli {
namespace {

namespace pb = haptics::v1;

pb::Frame FrameAt(int64_t step, uint64_t dropped, int64_t missed, int64_t off_cpu, int64_t clashes,
                  double clash_s) {
  pb::Frame frame;
  frame.set_step(step);
  frame.set_dropped_frames(dropped);
  frame.set_missed_steps(missed);
  frame.set_missed_steps_off_cpu(off_cpu);
  pb::ToolClash* a = frame.add_clashes();
  a->set_count(clashes);
  a->set_duration_s(clash_s);
  pb::ToolClash* b = frame.add_clashes();  // a second pair: summed
  b->set_count(1);
  b->set_duration_s(0.5);
  return frame;
}

// The counters count from the window's first frame: each is its growth
// from the first frame to the latest (what came before the window is not
// counted), clashes summed over the pairs; frames per second over the
// window.
TEST(FrameCountsTest, GrowthFromTheFirstFrame) {
  FrameCounts counts;
  counts.Add(FrameAt(100, 7, 3, 1, 2, 0.25));
  counts.Add(FrameAt(101, 7, 3, 1, 2, 0.25));
  counts.Add(FrameAt(110, 12, 6, 2, 5, 1.0));
  StreamReport report;
  counts.Fill(report, 2.0);
  EXPECT_EQ(counts.frames(), 3);
  EXPECT_EQ(report.frames, 3);
  EXPECT_EQ(report.first_step, 100);
  EXPECT_EQ(report.last_step, 110);
  EXPECT_EQ(report.dropped_frames, 5);
  EXPECT_EQ(report.missed_steps, 3);
  EXPECT_EQ(report.missed_steps_off_cpu, 1);
  EXPECT_EQ(report.tool_clashes, 3);
  EXPECT_DOUBLE_EQ(report.tool_clash_s, 0.75);
  EXPECT_DOUBLE_EQ(report.frames_per_s, 1.5);
}

// No frame: every count zero.
TEST(FrameCountsTest, NoFrames) {
  StreamReport report;
  FrameCounts().Fill(report, 1.0);
  EXPECT_EQ(report.frames, 0);
  EXPECT_EQ(report.last_step, 0);
  EXPECT_EQ(report.dropped_frames, 0);
  EXPECT_EQ(report.frames_per_s, 0);
}

}  // namespace
}  // namespace hs::cli

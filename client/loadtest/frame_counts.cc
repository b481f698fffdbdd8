#include "client/loadtest/frame_counts.h"

#include "client/frame_format.h"

namespace hs::cli {

void FrameCounts::Add(const haptics::v1::Frame& frame) {
  const bool first = frames_ == 0;
  ++frames_;
  step_.See(frame.step(), first);
  dropped_.See(static_cast<int64_t>(frame.dropped_frames()), first);
  missed_.See(frame.missed_steps(), first);
  missed_off_cpu_.See(frame.missed_steps_off_cpu(), first);
  const ClashTotals clashes = SumClashes(frame);
  clashes_.See(clashes.count, first);
  clash_s_.See(clashes.seconds, first);
}

void FrameCounts::Fill(StreamReport& report, double window_s) const {
  report.frames = frames_;
  report.first_step = step_.first;
  report.last_step = step_.last;
  report.dropped_frames = dropped_.Grown();
  report.missed_steps = missed_.Grown();
  report.missed_steps_off_cpu = missed_off_cpu_.Grown();
  report.tool_clashes = clashes_.Grown();
  report.tool_clash_s = clash_s_.Grown();
  report.frames_per_s = static_cast<double>(frames_) / window_s;
}

}  // namespace hs::cli

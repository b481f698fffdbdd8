#include "server/frame_message.h"

namespace hs {

void FillFrameMessage(const StepSnapshot& s, const FrameParts& parts, const std::string& tool,
                      uint64_t dropped, int64_t sent_unix_ns, haptics::v1::Frame& frame) {
  frame.Clear();
  frame.set_step(s.step);
  frame.set_time_s(s.time_s);
  StepFrameToProto(s.frame, *s.names, parts, &frame);
  for (size_t i = 0; i < s.frame.tools.size(); ++i) {
    const std::string& name = (*s.names)[s.frame.tools[i].tool];
    if (s.holders) {
      const auto holder = s.holders->find(name);
      if (holder != s.holders->end()) frame.mutable_tools(i)->set_holder(holder->second);
    }
    if (name != tool) continue;
    frame.set_last_pose_sequence(s.applied[i].sequence);
    frame.set_last_pose_device_time_ns(s.applied[i].device_time_ns);
  }
  haptics::v1::ServerTimings* timings = frame.mutable_timings();
  timings->set_step_ns(s.step_ns);
  timings->set_start_lag_ns(s.start_lag_ns);
  timings->set_sent_unix_ns(sent_unix_ns);
  frame.set_dropped_frames(dropped);
  frame.set_missed_steps(s.missed_steps);
  frame.set_missed_steps_off_cpu(s.missed_steps_off_cpu);
}

namespace {

constexpr size_t kFirstBlockBytes = 64 << 10;

}  // namespace

FrameMessageArena::FrameMessageArena() : block_(kFirstBlockBytes) { MakeArena(); }

void FrameMessageArena::MakeArena() {
  google::protobuf::ArenaOptions options;
  options.initial_block = block_.data();
  options.initial_block_size = block_.size();
  arena_.emplace(options);
}

haptics::v1::Frame& FrameMessageArena::Start() {
  if (arena_->SpaceAllocated() > block_.size()) {  // the last frame overflowed
    const size_t needed = arena_->SpaceAllocated();
    arena_.reset();
    block_.assign(2 * needed, 0);
    MakeArena();
  } else {
    arena_->Reset();
  }
  return *google::protobuf::Arena::CreateMessage<haptics::v1::Frame>(&*arena_);
}

}  // namespace hs

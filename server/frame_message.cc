#include "server/frame_message.h"

#include "common/api/local_model_convert.h"

namespace hs {

namespace {

// The holder of the tool of frame entry `i`, none when no device holds it.
const ToolHolder* HolderOf(const StepSnapshot& s, size_t i) {
  const ObjectId tool = s.frame.tools[i].tool;
  if (!s.holders || tool < 0 || static_cast<size_t>(tool) >= s.holders->size()) return nullptr;
  const ToolHolder& holder = (*s.holders)[tool];
  return holder.sink != nullptr ? &holder : nullptr;
}

// The tool `stream`'s device holds, -1 for none.
ObjectId OwnTool(const StepSnapshot& s, const FrameSink* stream) {
  for (size_t i = 0; i < s.frame.tools.size(); ++i) {
    const ToolHolder* holder = HolderOf(s, i);
    if (holder != nullptr && holder->sink == stream) return s.frame.tools[i].tool;
  }
  return -1;
}

}  // namespace

void FillFrameMessage(const StepSnapshot& s, const FrameParts& parts, const FrameSink* stream,
                      uint64_t dropped, int64_t sent_unix_ns, ModelsSent& sent,
                      haptics::v1::Frame& frame) {
  frame.Clear();
  frame.set_step(s.step);
  frame.set_time_s(s.time_s);
  FrameParts without_models = parts;
  without_models.local_model = false;
  // Until the step names the stream's device as its tool's holder (the
  // steps between attaching and the first frame of the new holder), its
  // frames carry every tool, as a viewer's.
  const ObjectId own_tool = sent.own_tool_only ? OwnTool(s, stream) : -1;
  if (own_tool >= 0) without_models.only_tool = own_tool;
  StepFrameToProto(s.frame, *s.names, without_models, &frame);
  if (sent.scene != s.names.get()) {  // a new scene: its models are new
    sent.scene = s.names.get();
    sent.revisions.clear();
    sent.surfaces.clear();
  }
  sent.revisions.resize(s.frame.tools.size(), 0);
  sent.surfaces.resize(s.frame.tools.size(), 0);
  int k = 0;  // the tool's entry in `frame`
  for (size_t i = 0; i < s.frame.tools.size(); ++i) {
    if (without_models.only_tool && *without_models.only_tool != s.frame.tools[i].tool) continue;
    haptics::v1::ToolState& state = *frame.mutable_tools(k++);
    const ToolHolder* holder = HolderOf(s, i);
    const bool own = holder != nullptr && holder->sink == stream;
    if (holder != nullptr) state.set_holder(holder->name);
    state.set_last_pose_sequence(s.applied[i].sequence);
    state.set_last_pose_device_time_ns(s.applied[i].device_time_ns);
    if (own) {
      frame.set_last_pose_sequence(s.applied[i].sequence);
      frame.set_last_pose_device_time_ns(s.applied[i].device_time_ns);
    }
    const LocalModel& model = s.frame.tools[i].local_model;
    if (parts.local_model && model.revision != 0 && sent.revisions[i] != model.revision &&
        (own || !sent.own_tool_only)) {
      LocalModelToProto(model, *s.names, state.mutable_local_model(),
                        sent.surfaces[i] != model.surface_revision());
      sent.revisions[i] = model.revision;
      sent.surfaces[i] = model.surface_revision();
    }
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

#pragma once
// The message a stream writes for one step: the snapshot's frame (the
// parts the stream asked for) with the server's extras (the device's last
// applied pose, timings, drops and misses).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/api/proto_convert.h"
#include "google/protobuf/arena.h"
#include "haptics/v1/session_service.pb.h"
#include "server/step_snapshot.h"

namespace hs {

/// The local models one stream has been sent: each revision goes out once,
/// and a frame without a tool's model means its last one still holds.
struct ModelsSent {
  /// A device stream gets its own tool's state and model only (all it
  /// renders from, and the least to send); a viewer every tool's.
  bool own_tool_only = false;
  /// The scene they were sent for (its StepSnapshot::names), and the
  /// revision sent for each of its frame's tools (0: none), and the
  /// surface whose faces it was sent (a model's surface goes out whole
  /// once; later models carry its revision alone).
  const void* scene = nullptr;
  std::vector<uint64_t> revisions;
  std::vector<uint64_t> surfaces;
};

/// Writes `s` over `frame` (cleared first). `stream` is the stream the
/// frame goes to: the tool its device holds (StepSnapshot::holders) gets
/// the last applied pose, and is the only tool in the frame when
/// `sent.own_tool_only` (every tool while no tool names the stream's
/// device as its holder). Local models (parts.local_model) go out as
/// `sent` says, which it updates. `dropped` the frames the stream dropped
/// so far, `sent_unix_ns` the wall clock at sending.
void FillFrameMessage(const StepSnapshot& s, const FrameParts& parts, const FrameSink* stream,
                      uint64_t dropped, int64_t sent_unix_ns, ModelsSent& sent,
                      haptics::v1::Frame& frame);

/// A stream's message for one step, built on an arena whose first block is
/// the stream's own and reset each step: building a frame allocates
/// nothing once the block holds the largest frame so far (a plain message
/// reused through Clear() would delete and allocate its sub-messages).
class FrameMessageArena {
 public:
  FrameMessageArena();
  /// An empty Frame on the arena, valid until the next Start. Grows the
  /// block first when the last frame overflowed it.
  haptics::v1::Frame& Start();

 private:
  void MakeArena();

  std::vector<char> block_;
  std::optional<google::protobuf::Arena> arena_;
};

}  // namespace hs

#pragma once
// A Device's configuration inside the SDK: the public options, and what
// only the project's own runs set (`hapticctl drive --operator`: more
// effects, a look at each frame, a simulated link under the stream).

#include <grpcpp/grpcpp.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "client/sdk/interact_stream.h"
#include "haptics/device.h"
#include "haptics/v1/session_service.pb.h"

namespace hs::sdk {

/// What one frame changed.
struct FrameRead {
  /// The stream's first frame: the device is connected.
  bool first_frame = false;
  /// The feed changed (a new stream, model or force): publish it.
  bool feed_changed = false;
  bool new_model = false;
  /// The frame carried a model that failed the checks (not rendered).
  bool model_rejected = false;
  /// The sequence of this stream's pose the frame applied, and from that
  /// pose's tick to now, nanoseconds; 0 and -1 when it applied none of
  /// them (none yet, or the tool's last device's).
  uint64_t applied_sequence = 0;
  int64_t round_trip_ns = -1;
};

/// Opens one stream: sends `open`, hands its frames to `callbacks`.
using OpenPipe = std::function<std::unique_ptr<InteractPipe>(
    const std::shared_ptr<grpc::Channel>& channel, const haptics::v1::InteractRequest::Open& open,
    InteractStream::Callbacks callbacks)>;

struct DeviceConfig {
  std::string scene;
  std::string tool;
  haptics::DeviceOptions options;
  /// The first frame of a stream comes within this, seconds, or the stream
  /// is given up.
  double open_timeout_s = 5;
  /// Effects asked for beyond the device's own (force, friction and, with
  /// options.local_model, the local model): an operator run reads the
  /// hand's depth from the contacts.
  std::vector<haptics::v1::Effect> extra_needs;
  /// Called with each frame the device has taken and what it read there
  /// (DeviceProtocol::Read), on the thread that reads the stream; null:
  /// none.
  std::function<void(const haptics::v1::Frame&, const FrameRead&)> on_frame;
  /// How each stream opens; null: an InteractStream on the channel.
  OpenPipe open_pipe;
};

}  // namespace hs::sdk

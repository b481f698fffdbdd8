#pragma once
// What a Device says on its Interact stream and what it reads from it,
// on no clock of its own: the Open, each pose's request (with what it asks
// of the server's model, model_request.h), and, from each frame, the
// stream's state, the tool's newest local model and force: the Feed its
// loop renders from (tick_renderer.h). The network thread (device_link.h)
// runs it on the steady clock over gRPC; a run on a simulated clock
// (tests/client/remote/simulated_device.h) runs the same over a simulated
// link, so that both speak as one device.

#include <array>
#include <atomic>
#include <cstdint>

#include "client/haptic_loop/model_request.h"
#include "client/sdk/device_config.h"
#include "client/sdk/device_feed.h"
#include "haptics/v1/session_service.pb.h"

namespace hs::sdk {

class DeviceProtocol {
 public:
  explicit DeviceProtocol(const DeviceConfig& config);

  /// The Open of every stream.
  haptics::v1::InteractRequest::Open Open() const;

  /// A new stream, `stream` (1 for the first): poses count from 1 again
  /// and the feed says it is not yet connected. Call before its first
  /// frame can be read.
  void Begin(uint64_t stream);
  /// The stream ended: the feed says so.
  void End();

  /// Writes over `request` the one carrying `sample`, the device's newest
  /// pose, with the stream's next sequence. `sample.time_ns` is the pose's
  /// time on the clock `Read`'s `now_ns` is on. Until a model of the
  /// stream's own poses comes, each pose asks for one (model_stale): the
  /// server sends each model once, and a link that loses it would leave the
  /// device without one while its hand waits.
  void PoseRequest(const PoseSample& sample, haptics::v1::InteractRequest& request);

  /// Takes `frame`, read at `now_ns`, into the feed: its force and model
  /// only once it applied one of this stream's poses (the first model
  /// comes a round trip after the first pose, built for it); then calls
  /// config.on_frame with the frame and what was read.
  FrameRead Read(const haptics::v1::Frame& frame, int64_t now_ns);

  const Feed& feed() const { return feed_; }

 private:
  // Read less the call to config.on_frame.
  FrameRead Take(const haptics::v1::Frame& frame, int64_t now_ns);

  const DeviceConfig& config_;
  // Poses and their requests: the sending thread's.
  ModelRequester model_requester_;
  // Poses sent on this stream, and the first one's time (0: none yet):
  // written by the sender, read by the reader.
  std::atomic<uint64_t> sequence_{0};
  std::atomic<int64_t> first_pose_time_ns_{0};
  // A model came on this stream: written by the reader, read by the sender.
  std::atomic<bool> has_model_{false};
  // The feed: the reading thread's while a stream runs, else the sending
  // thread's (Begin, End).
  Feed feed_;
  bool first_frame_ = false;
  uint64_t last_revision_ = 0;
  // The faces of the newest surfaces, newest at `surfaces_next_ - 1`: the
  // models that name one alone (by revision, centre and radius) get its
  // faces, so that the loop has them even when it never saw the model
  // that brought them (it takes the newest model at each tick). Kept here,
  // across streams too, while the tick's loop may hold one (it holds the
  // last two or three models' surfaces, and a surface lasts half a
  // validity radius of the proxy's travel), so that the last reference to
  // a surface, and its freeing, is the network thread's, not the tick's.
  std::array<std::shared_ptr<const ModelSurface>, 16> surfaces_;
  size_t surfaces_next_ = 0;
  // The longest round trip read since the last pose went (-1: none):
  // written by the reader, taken by the sender.
  std::atomic<int64_t> round_trip_peak_ns_{-1};
};

}  // namespace hs::sdk

#include "server/frame_pump.h"

#include <chrono>
#include <cmath>

#include "absl/strings/str_cat.h"
#include "common/core/check.h"
#include "server/raw_message.h"

namespace hs {
namespace {

int64_t UnixNanoseconds() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

}  // namespace

absl::StatusOr<double> CheckFrameRate(double frame_rate_hz, double scene_rate_hz,
                                      const char* field) {
  if (frame_rate_hz == 0) return 0.0;
  // Rounding of the scene's rate (1 / step_s) must not refuse the rate itself.
  if (!std::isfinite(frame_rate_hz) || frame_rate_hz < 1 ||
      frame_rate_hz > scene_rate_hz * (1 + 1e-9)) {
    return absl::InvalidArgumentError(absl::StrCat(field, ": ", frame_rate_hz,
                                                   " frames a second is outside 1 to the scene's ",
                                                   scene_rate_hz, " (0: every step)"));
  }
  return frame_rate_hz;
}

FramePump::FramePump(FrameWriter& writer, const FrameSink* stream, Metrics& metrics)
    : writer_(writer), stream_(stream), metrics_(metrics), outbox_(kViewerQueueFrames) {}

void FramePump::Configure(const Options& options) {
  HS_CHECK(options.queue_frames >= 1 && options.queue_frames <= kViewerQueueFrames);
  options_ = options;
  models_sent_.own_tool_only = options.device;
  outbox_.Limit(options.frame_rate_hz > 0 ? 1 : options.queue_frames);
}

bool FramePump::Due(const StepSnapshot& snapshot) {
  if (options_.frame_rate_hz <= 0) return true;
  if (snapshot.time_s + kFrameDueSlackS < next_due_s_) return false;
  // The next due time is the next multiple of the period: streams of one
  // rate take the same steps whenever they began, so the scene's frames
  // thread wakes once for all of them (FrameFanOut). The first frame goes
  // at once; after a stall the rate starts again with no burst.
  const double period_s = 1 / options_.frame_rate_hz;
  next_due_s_ = (std::floor((snapshot.time_s + kFrameDueSlackS) / period_s) + 1) * period_s;
  return true;
}

void FramePump::Offer(std::shared_ptr<const StepSnapshot> snapshot) {
  if (!Due(*snapshot)) return;
  if (outbox_.Push(std::move(snapshot))) metrics_.AddFramesDropped(1);
  Pump();
}

void FramePump::Close(const absl::Status& status) {
  outbox_.Close(status);
  Pump();
}

void FramePump::Abort(const absl::Status& status) {
  outbox_.Abort(status);
  Pump();
}

void FramePump::WriteDone(bool ok) {
  outbox_.WriteDone();
  if (ok) {
    metrics_.AddFramesSent(1);
    Pump();
  } else {
    Abort(absl::CancelledError("the client is gone"));
  }
}

void FramePump::Pump() {
  const FrameOutbox::Next next = outbox_.TakeNext();
  if (next.kind == FrameOutbox::Next::kWrite) {
    haptics::v1::Frame& frame = frame_.Start();
    FillFrameMessage(*next.snapshot, options_.parts, stream_, next.dropped, UnixNanoseconds(),
                     models_sent_, frame);
    absl::Status status;
    if (frame.ByteSizeLong() > options_.max_frame_bytes) {
      status = absl::ResourceExhaustedError(
          absl::StrCat("a frame of ", frame.ByteSizeLong(), " bytes is over the ",
                       options_.max_frame_bytes, " a stream sends: ask for fewer parts"));
    } else {
      status = SerializeMessage(frame, bytes_);
    }
    if (!status.ok()) {
      // Ends this stream only; the stream detaches when its RPC is done.
      outbox_.WriteDone();
      Abort(status);
      return;
    }
    writer_.StartWrite(&bytes_);
  } else if (next.kind == FrameOutbox::Next::kFinish) {
    std::lock_guard lock(finish_mu_);
    writer_.Finish(next.status);
  }
}

}  // namespace hs

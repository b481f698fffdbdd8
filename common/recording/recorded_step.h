#pragma once
// What a recording keeps of a step, built alike by the server as it
// records and by replay as it re-runs: the frame as a stream sees it, less
// the server's timings and stream counters (which no re-run repeats), or
// its digest; and device poses exactly as the scene took them.

#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "common/sim/effects.h"
#include "common/sim/step_frame.h"
#include "haptics/v1/recording.pb.h"

namespace hs {

/// Fills `out` with step `step` (simulated time `time_s` at its end):
/// `frame` (object names by id in `names`) in full, or its SHA-256 when
/// `mode` is FRAME_RECORDING_DIGEST, and the `needs` it was stepped with.
void FillRecordedFrame(int64_t step, double time_s, const StepFrame& frame,
                       const std::vector<std::string>& names, EffectSet needs,
                       haptics::v1::FrameRecording mode, haptics::v1::RecordedFrame* out);

/// The SHA-256 of `frame` serialized deterministically.
std::string FrameDigest(const haptics::v1::Frame& frame);

/// `X` bit for bit.
void ExactPoseToProto(const Isometry3d& X, haptics::v1::ExactPose* out);
/// The pose ExactPoseToProto wrote. INVALID_ARGUMENT for a wrong count of
/// numbers or a number that is not finite.
absl::StatusOr<Isometry3d> ExactPoseFromProto(const haptics::v1::ExactPose& pose);

}  // namespace hs

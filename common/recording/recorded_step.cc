#include "common/recording/recorded_step.h"

#include <cmath>

#include "common/api/proto_convert.h"
#include "common/hash/sha256.h"
#include "google/protobuf/io/coded_stream.h"
#include "google/protobuf/io/zero_copy_stream_impl_lite.h"

namespace hs {

std::string FrameDigest(const haptics::v1::Frame& frame) {
  std::string bytes;
  {
    google::protobuf::io::StringOutputStream stream(&bytes);
    google::protobuf::io::CodedOutputStream coded(&stream);
    coded.SetSerializationDeterministic(true);
    frame.SerializeToCodedStream(&coded);
  }
  return Sha256Of(bytes);
}

void FillRecordedFrame(int64_t step, double time_s, const StepFrame& frame,
                       const std::vector<std::string>& names, EffectSet needs,
                       haptics::v1::FrameRecording mode, haptics::v1::RecordedFrame* out) {
  out->Clear();
  out->set_step(step);
  EffectsToProto(needs, out->mutable_needs());
  haptics::v1::Frame* message = out->mutable_frame();
  message->set_step(step);
  message->set_time_s(time_s);
  StepFrameToProto(frame, names, FrameParts{}, message);
  if (mode == haptics::v1::FRAME_RECORDING_DIGEST) out->set_sha256(FrameDigest(*message));
}

void ExactPoseToProto(const Isometry3d& X, haptics::v1::ExactPose* out) {
  out->Clear();
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) out->add_rotation_row_major(X.linear()(row, col));
  }
  VectorToProto(X.translation(), out->mutable_translation_m());
}

absl::StatusOr<Isometry3d> ExactPoseFromProto(const haptics::v1::ExactPose& pose) {
  if (pose.rotation_row_major_size() != 9) {
    return absl::InvalidArgumentError("device_pose: the rotation needs 9 numbers");
  }
  Isometry3d X = Isometry3d::Identity();
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) {
      const double v = pose.rotation_row_major(3 * row + col);
      if (!std::isfinite(v)) return absl::InvalidArgumentError("device_pose: not finite");
      X.linear()(row, col) = v;
    }
  }
  const haptics::v1::Vector3& t = pose.translation_m();
  if (!std::isfinite(t.x()) || !std::isfinite(t.y()) || !std::isfinite(t.z())) {
    return absl::InvalidArgumentError("device_pose: not finite");
  }
  X.translation() = Vector3d(t.x(), t.y(), t.z());
  return X;
}

}  // namespace hs

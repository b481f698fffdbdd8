#include "common/api/frame_scoring.h"

#include "common/api/proto_convert.h"

namespace hs {

ScoringFrame ScoringFrameFromProto(const haptics::v1::Frame& frame, const std::string& tool,
                                   FrameStream stream) {
  ScoringFrame out{.time_s = frame.time_s()};
  // Before the device's first pose the tool rests where the scene put it,
  // at no time of the device's.
  if (stream == FrameStream::kToolsDevice && frame.last_pose_sequence() > 0) {
    out.pose_time_s = DevicePoseTime(frame.last_pose_device_time_ns());
  }
  auto vector = [](const haptics::v1::Vector3& v) {
    absl::StatusOr<Vector3d> read = VectorFromProto(v, "frame");
    return read.ok() ? *read : Vector3d::Zero();
  };
  for (const haptics::v1::ToolState& t : frame.tools()) {
    if (t.tool() != tool) continue;
    // Every stream's frames say each tool's last pose (ToolState).
    if (!out.pose_time_s && t.last_pose_sequence() > 0) {
      out.pose_time_s = DevicePoseTime(t.last_pose_device_time_ns());
    }
    out.p_WD = vector(t.device_pose().position_m());
    out.force_W = vector(t.force_w_n());
    for (const haptics::v1::Contact& c : t.contacts()) {
      ScoringContact contact{.object = c.object()};
      for (const haptics::v1::ContactPoint& p : c.points()) {
        contact.points_W.push_back(vector(p.p_wc_m()));
      }
      out.contacts.push_back(std::move(contact));
    }
  }
  return out;
}

}  // namespace hs

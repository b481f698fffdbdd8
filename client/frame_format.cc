#include "client/frame_format.h"

#include "client/server_call.h"

namespace hs::cli {
namespace {

namespace pb = haptics::v1;

std::ostream& operator<<(std::ostream& out, const pb::Vector3& v) {
  return out << "(" << v.x() << ", " << v.y() << ", " << v.z() << ")";
}

}  // namespace

void PrintFrame(const pb::Frame& frame, bool json, std::ostream& out) {
  if (json) {
    out << ProtoToJsonLine(frame) << "\n";
    return;
  }
  out << "step " << frame.step() << " pose " << frame.last_pose_sequence();
  for (const pb::ToolState& tool : frame.tools()) {
    out << "  " << tool.tool();
    if (!tool.holder().empty()) out << " (held by " << tool.holder() << ")";
    out << ": " << tool.contacts_size() << " contact(s)";
    for (const pb::Contact& c : tool.contacts()) {
      out << " [" << c.object() << (c.penetrating() ? " penetrating" : " touching") << ", depth "
          << c.depth_m() << " m, normal " << c.normal_w() << "]";
    }
    out << ", force " << tool.force_w_n() << " N";
  }
  for (const pb::ToolClash& clash : frame.clashes()) {
    if (clash.touching()) out << "  clash " << clash.tool_a() << "-" << clash.tool_b();
  }
  // A count since the stream began, not this frame's.
  if (frame.dropped_frames() > 0) {
    out << "  (" << frame.dropped_frames() << " frames dropped so far)";
  }
  out << "\n";
}

ClashTotals SumClashes(const pb::Frame& frame) {
  ClashTotals totals;
  for (const pb::ToolClash& clash : frame.clashes()) {
    totals.count += clash.count();
    totals.seconds += clash.duration_s();
  }
  return totals;
}

}  // namespace hs::cli

#include "client/sdk/frame_view.h"

namespace hs::sdk {
namespace {

namespace pb = haptics::v1;

void Copy(const pb::Vector3& v, double out[3]) {
  out[0] = v.x();
  out[1] = v.y();
  out[2] = v.z();
}

haptics::Pose PoseFromProto(const pb::Pose& pose) {
  haptics::Pose out;
  Copy(pose.position_m(), out.position_m);
  if (pose.has_orientation()) {
    const pb::Quaternion& q = pose.orientation();
    out.orientation_wxyz[0] = q.w();
    out.orientation_wxyz[1] = q.x();
    out.orientation_wxyz[2] = q.y();
    out.orientation_wxyz[3] = q.z();
  }
  return out;
}

haptics::Contact ContactFromProto(const pb::Contact& c) {
  haptics::Contact out;
  out.object = c.object();
  out.colliding = c.colliding();
  out.penetrating = c.penetrating();
  out.depth_m = c.depth_m();
  Copy(c.normal_w(), out.normal_w);
  for (const pb::ContactPoint& p : c.points()) {
    out.points_w_m.insert(out.points_w_m.end(), {p.p_wc_m().x(), p.p_wc_m().y(), p.p_wc_m().z()});
  }
  if (c.has_time_of_impact()) out.time_of_impact = c.time_of_impact();
  return out;
}

haptics::LocalModel ModelFromProto(const pb::LocalModel& m) {
  haptics::LocalModel out;
  out.revision = m.revision();
  out.proxy_pose = PoseFromProto(m.proxy_pose());
  out.validity_radius_m = m.validity_radius_m();
  out.force_clamp_n = m.force_clamp_n();
  out.touching = m.touching();
  for (const pb::ConstraintPlane& p : m.planes()) {
    haptics::Plane plane;
    plane.object = p.object();
    Copy(p.point_w_m(), plane.point_w_m);
    Copy(p.normal_w(), plane.normal_w);
    plane.gap_m = p.gap_m();
    plane.stiffness_n_per_m = p.material().stiffness_n_per_m();
    plane.damping_ns_per_m = p.material().damping_ns_per_m();
    plane.separating = p.separating();
    out.planes.push_back(std::move(plane));
  }
  return out;
}

}  // namespace

haptics::Frame FrameFromProto(const pb::Frame& frame) {
  haptics::Frame out;
  out.step = frame.step();
  out.time_s = frame.time_s();
  out.dropped_frames = frame.dropped_frames();
  out.missed_steps = frame.missed_steps();
  for (const pb::ToolState& t : frame.tools()) {
    haptics::ToolFrame tool;
    tool.tool = t.tool();
    tool.holder = t.holder();
    tool.device_pose = PoseFromProto(t.device_pose());
    tool.proxy_pose = PoseFromProto(t.proxy_pose());
    Copy(t.force_w_n(), tool.force_n);
    Copy(t.torque_w_nm(), tool.torque_nm);
    tool.force_clamped = t.force_clamped();
    for (const pb::Contact& c : t.contacts()) tool.contacts.push_back(ContactFromProto(c));
    tool.has_local_model = t.has_local_model();
    if (tool.has_local_model) tool.local_model = ModelFromProto(t.local_model());
    out.tools.push_back(std::move(tool));
  }
  return out;
}

}  // namespace hs::sdk

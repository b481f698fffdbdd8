#include "client/viewer/viewer_json.h"

#include "common/api/object_kind_name.h"

namespace hs::cli {
namespace {

namespace pb = haptics::v1;
using nlohmann::json;

json Vec(const pb::Vector3& v) { return json::array({v.x(), v.y(), v.z()}); }

json PoseJson(const pb::Pose& pose) {
  const pb::Quaternion& q = pose.orientation();
  return {{"p", Vec(pose.position_m())}, {"q", json::array({q.w(), q.x(), q.y(), q.z()})}};
}

const char* KindName(pb::FeatureKind kind) {
  switch (kind) {
    case pb::FEATURE_KIND_VERTEX:
      return "vertex";
    case pb::FEATURE_KIND_EDGE:
      return "edge";
    case pb::FEATURE_KIND_FACE:
      return "face";
    default:
      return "none";
  }
}

json SideJson(const pb::SideContact& side) {
  return {{"vertices", side.vertices()}, {"edges", side.edges()}, {"faces", side.faces()}};
}

json ContactJson(const pb::Contact& c) {
  json points = json::array();
  for (const pb::ContactPoint& p : c.points()) points.push_back(Vec(p.p_wc_m()));
  return {{"object", c.object()},
          {"kind", KindName(c.object_side().kind())},
          {"depth_m", c.depth_m()},
          {"colliding", c.colliding()},
          {"penetrating", c.penetrating()},
          {"reversing_vector_m", Vec(c.reversing_vector_w_m())},
          {"normal", Vec(c.normal_w())},
          {"points", points},
          {"tool_side", SideJson(c.tool_side())},
          {"object_side", SideJson(c.object_side())}};
}

}  // namespace

json FrameJson(const pb::Frame& frame, const FrameExtras& extras) {
  json tools = json::array();
  for (const pb::ToolState& t : frame.tools()) {
    json contacts = json::array();
    for (const pb::Contact& c : t.contacts()) contacts.push_back(ContactJson(c));
    const auto page = extras.page_holders.find(t.tool());
    tools.push_back({{"name", t.tool()},
                     {"holder", page == extras.page_holders.end() ? t.holder() : page->second},
                     {"device", PoseJson(t.device_pose())},
                     {"proxy", PoseJson(t.proxy_pose())},
                     {"force_n", Vec(t.force_w_n())},
                     {"torque_nm", Vec(t.torque_w_nm())},
                     {"force_clamped", t.force_clamped()},
                     {"contacts", contacts}});
  }
  json bodies = json::array();
  for (const pb::BodyState& b : frame.bodies()) {
    bodies.push_back({{"name", b.name()},
                      {"pose", PoseJson(b.pose())},
                      {"touching_tools", b.touching_tools()},
                      {"held", b.held()}});
  }
  return {{"type", "frame"},
          {"step", frame.step()},
          {"time_s", frame.time_s()},
          {"revision", extras.revision},
          {"age_ms", extras.age_ms},
          {"step_rate_hz", extras.step_rate_hz},
          {"dropped_frames", extras.dropped_frames},
          {"missed_steps", frame.missed_steps()},
          {"tools", tools},
          {"bodies", bodies}};
}

json GeometryJson(const pb::SceneGeometry& geometry) {
  json objects = json::array();
  for (const pb::ObjectGeometry& o : geometry.objects()) {
    json materials = json::array();
    for (const pb::Material& m : o.materials()) {
      materials.push_back({{"stiffness_n_per_m", m.stiffness_n_per_m()},
                           {"damping_ns_per_m", m.damping_ns_per_m()},
                           {"static_friction", m.static_friction()},
                           {"dynamic_friction", m.dynamic_friction()}});
    }
    objects.push_back({{"name", o.name()},
                       {"kind", ObjectKindName(o.kind())},
                       {"pose", PoseJson(o.pose())},
                       {"vertices", o.vertices_m()},
                       {"triangles", o.triangles()},
                       {"edges", o.edges()},
                       {"face_materials", o.face_materials()},
                       {"materials", materials}});
  }
  return {{"scene", geometry.scene()}, {"revision", geometry.revision()}, {"objects", objects}};
}

}  // namespace hs::cli

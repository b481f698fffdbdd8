#include "client/contact_json.h"

#include <cmath>

namespace hs::cli {
namespace {

nlohmann::ordered_json Side(const SideContact& side) {
  return {{"kind", FeatureKindName(side.kind)},
          {"vertices", side.vertices},
          {"edges", side.edges},
          {"faces", side.faces}};
}

nlohmann::ordered_json FeatureJson(const Feature& f) {
  return {{"kind", FeatureKindName(f.kind)}, {"id", f.id}};
}

}  // namespace

nlohmann::ordered_json Vector3Json(const Vector3d& v) { return {v.x(), v.y(), v.z()}; }

const char* FeatureKindName(FeatureKind kind) {
  switch (kind) {
    case FeatureKind::kVertex:
      return "vertex";
    case FeatureKind::kEdge:
      return "edge";
    case FeatureKind::kFace:
      return "face";
    case FeatureKind::kNone:
      break;
  }
  return "none";
}

nlohmann::ordered_json ContactSetToJson(const ContactSet& set) {
  nlohmann::ordered_json points = nlohmann::ordered_json::array();
  for (const ContactPoint& p : set.points) {
    points.push_back({{"p_WC_m", Vector3Json(p.p_WC)},
                      {"moving", FeatureJson(p.moving)},
                      {"fixed", FeatureJson(p.fixed)}});
  }
  nlohmann::ordered_json plane_depths = nlohmann::ordered_json::array();
  for (double d : set.plane_depths_m) {
    plane_depths.push_back(std::isfinite(d) ? nlohmann::ordered_json(d) : nullptr);
  }
  return {{"method", set.method == ContactMethod::kPaper2d ? "paper" : "3d"},
          {"colliding", set.colliding},
          {"penetrating", set.penetrating},
          {"depth_m", set.depth_m},
          {"direction_W", Vector3Json(set.direction_W)},
          {"reversing_vector_W_m", Vector3Json(set.reversing_vector_W)},
          {"normal_W", Vector3Json(set.normal_W)},
          {"tolerance_m", set.tolerance_m},
          {"singular_case", set.singular_case},
          {"fallback", set.fallback},
          {"time_of_impact",
           set.time_of_impact ? nlohmann::ordered_json(*set.time_of_impact) : nullptr},
          {"plane_depths_m", plane_depths},
          {"moving", Side(set.moving)},
          {"fixed", Side(set.fixed)},
          {"points", points}};
}

}  // namespace hs::cli

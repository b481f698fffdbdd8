#include "common/api/local_model_convert.h"

#include <algorithm>
#include <cmath>
#include <string_view>

#include "absl/strings/str_cat.h"
#include "common/api/proto_convert.h"
#include "common/core/status_macros.h"

namespace hs {
namespace {

namespace pb = haptics::v1;

// A finite number in [low, high], else INVALID_ARGUMENT naming `where`.
absl::StatusOr<double> NumberIn(double value, double low, double high, const std::string& where) {
  if (!(std::isfinite(value) && value >= low && value <= high)) {
    return InvalidField(where, absl::StrCat("must be finite and in [", low, ", ", high, "]"));
  }
  return value;
}

absl::StatusOr<ConstraintPlane> PlaneFromProto(const pb::ConstraintPlane& p,
                                               const std::string& at) {
  ConstraintPlane plane;
  HS_ASSIGN_OR_RETURN(plane.point_W, VectorFromProto(p.point_w_m(), at + ".point_W_m"));
  HS_ASSIGN_OR_RETURN(plane.normal_W, VectorFromProto(p.normal_w(), at + ".normal_W"));
  if (std::abs(plane.normal_W.norm() - 1) > 1e-6) return InvalidField(at + ".normal_W", "not unit");
  HS_ASSIGN_OR_RETURN(plane.gap_m, NumberIn(p.gap_m(), 0, kMaxCoordinate, at + ".gap_m"));
  HS_ASSIGN_OR_RETURN(plane.tool_point_W,
                      VectorFromProto(p.tool_point_w_m(), at + ".tool_point_W_m"));
  const pb::Material& m = p.material();
  const std::string mat = at + ".material";
  HS_ASSIGN_OR_RETURN(plane.stiffness_n_per_m,
                      NumberIn(m.stiffness_n_per_m(), 0, 1e9, mat + ".stiffness_n_per_m"));
  if (!(plane.stiffness_n_per_m > 0))
    return InvalidField(mat + ".stiffness_n_per_m", "must be > 0");
  HS_ASSIGN_OR_RETURN(plane.damping_ns_per_m,
                      NumberIn(m.damping_ns_per_m(), 0, 1e9, mat + ".damping_ns_per_m"));
  HS_ASSIGN_OR_RETURN(plane.static_friction,
                      NumberIn(m.static_friction(), 0, 1e3, mat + ".static_friction"));
  HS_ASSIGN_OR_RETURN(
      plane.dynamic_friction,
      NumberIn(m.dynamic_friction(), 0, plane.static_friction, mat + ".dynamic_friction"));
  plane.separating = p.separating();
  return plane;
}

}  // namespace

void LocalModelToProto(const LocalModel& model, const std::vector<std::string>& names,
                       pb::LocalModel* out) {
  PoseToProto(model.X_WP, out->mutable_proxy_pose());
  out->set_validity_radius_m(model.validity_radius_m);
  out->set_force_clamp_n(model.force_clamp_n);
  out->set_friction(model.friction);
  out->set_touching(model.touching);
  VectorToProto(model.touch_point_W, out->mutable_touch_point_w_m());
  VectorToProto(model.p_WD, out->mutable_device_position_w_m());
  out->set_revision(model.revision);
  for (const ConstraintPlane& plane : model.planes) {
    pb::ConstraintPlane* p = out->add_planes();
    p->set_object(names[plane.object]);
    VectorToProto(plane.point_W, p->mutable_point_w_m());
    VectorToProto(plane.normal_W, p->mutable_normal_w());
    p->set_gap_m(plane.gap_m);
    VectorToProto(plane.tool_point_W, p->mutable_tool_point_w_m());
    pb::Material* m = p->mutable_material();
    m->set_stiffness_n_per_m(plane.stiffness_n_per_m);
    m->set_damping_ns_per_m(plane.damping_ns_per_m);
    m->set_static_friction(plane.static_friction);
    m->set_dynamic_friction(plane.dynamic_friction);
    p->set_separating(plane.separating);
  }
}

absl::StatusOr<LocalModel> LocalModelFromProto(const pb::LocalModel& model) {
  LocalModel out;
  HS_ASSIGN_OR_RETURN(out.X_WP, PoseFromProto(model.proxy_pose(), "local_model.proxy_pose"));
  HS_ASSIGN_OR_RETURN(out.validity_radius_m, NumberIn(model.validity_radius_m(), 0, kMaxCoordinate,
                                                      "local_model.validity_radius_m"));
  if (!(out.validity_radius_m > 0))
    return InvalidField("local_model.validity_radius_m", "must be > 0");
  HS_ASSIGN_OR_RETURN(out.force_clamp_n,
                      NumberIn(model.force_clamp_n(), 0, 1e6, "local_model.force_clamp_n"));
  if (!(out.force_clamp_n > 0)) return InvalidField("local_model.force_clamp_n", "must be > 0");
  out.revision = model.revision();
  out.friction = model.friction();
  out.touching = model.touching();
  HS_ASSIGN_OR_RETURN(out.touch_point_W,
                      VectorFromProto(model.touch_point_w_m(), "local_model.touch_point_W_m"));
  HS_ASSIGN_OR_RETURN(
      out.p_WD, VectorFromProto(model.device_position_w_m(), "local_model.device_position_W_m"));
  out.planes.reserve(model.planes_size());
  // The planes' objects, numbered in the order the model first names them:
  // a device tells one object's planes from another's by them.
  std::vector<std::string_view> objects;
  for (int i = 0; i < model.planes_size(); ++i) {
    HS_ASSIGN_OR_RETURN(
        ConstraintPlane plane,
        PlaneFromProto(model.planes(i), absl::StrCat("local_model.planes[", i, "]")));
    const std::string_view name = model.planes(i).object();
    const auto known = std::find(objects.begin(), objects.end(), name);
    plane.object = static_cast<int32_t>(known - objects.begin());
    if (known == objects.end()) objects.push_back(name);
    out.planes.push_back(plane);
  }
  return out;
}

}  // namespace hs

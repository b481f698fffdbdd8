#include "common/api/proto_convert.h"

#include <algorithm>
#include <cmath>

#include "absl/strings/str_cat.h"
#include "common/api/local_model_convert.h"
#include "common/core/status_macros.h"

namespace hs {
namespace {

namespace pb = haptics::v1;

void FeatureToProto(const Feature& f, pb::Feature* out) {
  out->set_kind(static_cast<pb::FeatureKind>(f.kind));
  out->set_id(f.id);
}

void SideToProto(const SideContact& side, pb::SideContact* out) {
  out->set_kind(static_cast<pb::FeatureKind>(side.kind));
  out->mutable_vertices()->Add(side.vertices.begin(), side.vertices.end());
  out->mutable_edges()->Add(side.edges.begin(), side.edges.end());
  out->mutable_faces()->Add(side.faces.begin(), side.faces.end());
}

void ContactToProto(const PairContact& pair, const std::vector<std::string>& names,
                    pb::Contact* out) {
  const ContactSet& c = pair.contact;
  out->set_object(names[pair.object]);
  out->set_colliding(c.colliding);
  out->set_penetrating(c.penetrating);
  out->set_depth_m(c.depth_m);
  VectorToProto(c.direction_W, out->mutable_direction_w());
  VectorToProto(c.reversing_vector_W, out->mutable_reversing_vector_w_m());
  VectorToProto(c.normal_W, out->mutable_normal_w());
  SideToProto(c.moving, out->mutable_tool_side());
  SideToProto(c.fixed, out->mutable_object_side());
  for (const ContactPoint& p : c.points) {
    pb::ContactPoint* point = out->add_points();
    VectorToProto(p.p_WC, point->mutable_p_wc_m());
    FeatureToProto(p.moving, point->mutable_moving());
    FeatureToProto(p.fixed, point->mutable_fixed());
  }
  out->set_tolerance_m(c.tolerance_m);
  if (c.time_of_impact) {
    out->set_time_of_impact(*c.time_of_impact);
    out->set_has_time_of_impact(true);
  }
}

}  // namespace

absl::Status InvalidField(const std::string& where, const std::string& what) {
  return absl::InvalidArgumentError(absl::StrCat(where, ": ", what));
}

absl::StatusOr<Vector3d> VectorFromProto(const pb::Vector3& v, const std::string& where) {
  const Vector3d out(v.x(), v.y(), v.z());
  if (!out.allFinite()) return InvalidField(where, "not finite");
  if (out.cwiseAbs().maxCoeff() > kMaxCoordinate) {
    return InvalidField(where, absl::StrCat("beyond +-", kMaxCoordinate));
  }
  return out;
}

absl::StatusOr<Isometry3d> PoseFromProto(const pb::Pose& pose, const std::string& where) {
  HS_ASSIGN_OR_RETURN(const Vector3d p, VectorFromProto(pose.position_m(), where + ".position_m"));
  const pb::Quaternion& q = pose.orientation();
  Eigen::Quaterniond rotation(q.w(), q.x(), q.y(), q.z());
  if (!rotation.coeffs().allFinite()) return InvalidField(where + ".orientation", "not finite");
  if (rotation.coeffs().isZero()) {
    rotation = Eigen::Quaterniond::Identity();
  } else if (std::abs(rotation.norm() - 1) > 1e-6) {
    return InvalidField(where + ".orientation", "not a unit quaternion");
  }
  Isometry3d X = Isometry3d::Identity();
  X.linear() = rotation.normalized().toRotationMatrix();
  X.translation() = p;
  return X;
}

void VectorToProto(const Vector3d& v, pb::Vector3* out) {
  out->set_x(v.x());
  out->set_y(v.y());
  out->set_z(v.z());
}

void PoseToProto(const Isometry3d& X, pb::Pose* out) {
  VectorToProto(X.translation(), out->mutable_position_m());
  const Eigen::Quaterniond q(X.linear());
  pb::Quaternion* o = out->mutable_orientation();
  o->set_w(q.w());
  o->set_x(q.x());
  o->set_y(q.y());
  o->set_z(q.z());
}

absl::StatusOr<EffectSet> EffectsFromProto(const google::protobuf::RepeatedField<int>& effects,
                                           EffectSet empty_means, const std::string& where) {
  if (effects.empty()) return empty_means;
  EffectSet out;
  for (int i = 0; i < effects.size(); ++i) {
    const int e = effects.Get(i);
    if (e <= pb::EFFECT_UNSPECIFIED || e > kNumEffects) {
      return InvalidField(absl::StrCat(where, "[", i, "]"), "unknown effect");
    }
    // The proto's effects follow Effect's order, from 1.
    out = out.With(static_cast<Effect>(e - 1));
  }
  return out;
}

static_assert(pb::Effect_MAX == kNumEffects, "haptics.v1.Effect and Effect must match");

pb::Effect EffectToProto(Effect effect) {
  return static_cast<pb::Effect>(static_cast<int>(effect) + 1);
}

void EffectsToProto(EffectSet effects, google::protobuf::RepeatedField<int>* out) {
  for (int i = 0; i < kNumEffects; ++i) {
    const auto effect = static_cast<Effect>(i);
    if (effects.Has(effect)) out->Add(EffectToProto(effect));
  }
}

namespace {

bool IsTool(const StepFrame& frame, ObjectId id) {
  return std::any_of(frame.tools.begin(), frame.tools.end(),
                     [id](const ToolFrame& t) { return t.tool == id; });
}

void BodiesToProto(const StepFrame& frame, const std::vector<std::string>& names, pb::Frame* out) {
  for (const BodyFrame& b : frame.bodies) {
    pb::BodyState* body = out->add_bodies();
    body->set_name(names[b.body]);
    PoseToProto(b.X_WO, body->mutable_pose());
    for (const ObjectId other : b.touching) {
      if (IsTool(frame, other)) body->add_touching_tools(names[other]);
    }
    body->set_held(!b.touching.empty() &&
                   body->touching_tools_size() == static_cast<int>(b.touching.size()));
  }
}

}  // namespace

void StepFrameToProto(const StepFrame& frame, const std::vector<std::string>& names,
                      const FrameParts& parts, pb::Frame* out) {
  out->clear_tools();
  out->clear_stages_run();
  EffectsToProto(frame.stages_run, out->mutable_stages_run());
  for (const ToolFrame& t : frame.tools) {
    if (parts.only_tool && *parts.only_tool != t.tool) continue;
    pb::ToolState* tool = out->add_tools();
    tool->set_tool(names[t.tool]);
    if (parts.poses) {
      PoseToProto(t.X_WD, tool->mutable_device_pose());
      PoseToProto(t.X_WP, tool->mutable_proxy_pose());
    }
    if (parts.forces) {
      VectorToProto(t.force_W, tool->mutable_force_w_n());
      VectorToProto(t.torque_W, tool->mutable_torque_w_nm());
      tool->set_force_clamped(t.force_clamped);
    }
    if (parts.contacts) {
      for (const PairContact& c : t.contacts) ContactToProto(c, names, tool->add_contacts());
    }
    if (parts.local_model && frame.stages_run.Has(Effect::kLocalModel)) {
      // A surface's faces go to a stream once (server/frame_message.cc);
      // here, as in recordings, its revision stands for them.
      LocalModelToProto(t.local_model, names, tool->mutable_local_model(), false);
    }
  }
  out->clear_bodies();
  if (parts.bodies && frame.stages_run.Has(Effect::kFreeBodyMotion)) {
    BodiesToProto(frame, names, out);
  }
  out->clear_clashes();
  if (!parts.contacts) return;
  for (const ToolClash& c : frame.clashes) {
    pb::ToolClash* clash = out->add_clashes();
    clash->set_tool_a(names[c.tool_a]);
    clash->set_tool_b(names[c.tool_b]);
    clash->set_count(c.count);
    clash->set_duration_s(c.seconds);
    clash->set_touching(c.touching);
  }
}

}  // namespace hs

#include "client/loadtest/loadtest_scene.h"

#include <cmath>

#include "common/api/proto_convert.h"

namespace hs::cli {

namespace pb = haptics::v1;

pb::SceneSpec BuiltInLoadScene() {
  pb::SceneSpec spec;
  spec.set_name("probe on torus");
  spec.set_step_s(0.001);
  spec.set_force_clamp_n(10);
  pb::SceneObject* table = spec.add_objects();
  table->set_name("table");
  table->set_kind(pb::OBJECT_KIND_FIXED);
  VectorToProto(Vector3d(1, 1, 0.05),
                table->mutable_model()->mutable_procedural()->mutable_box()->mutable_size_m());
  VectorToProto(Vector3d(0, 0, -0.025), table->mutable_pose()->mutable_position_m());
  pb::SceneObject* organ = spec.add_objects();
  organ->set_name("organ");
  organ->set_kind(pb::OBJECT_KIND_FIXED);
  pb::Procedural::Torus* torus = organ->mutable_model()->mutable_procedural()->mutable_torus();
  torus->set_major_radius_m(0.1);
  torus->set_minor_radius_m(0.04);
  torus->set_major_segments(96);
  torus->set_minor_segments(48);
  VectorToProto(Vector3d(0, 0, 0.04), organ->mutable_pose()->mutable_position_m());
  pb::Material* material = organ->add_materials()->mutable_material();
  material->set_stiffness_n_per_m(400);
  material->set_damping_ns_per_m(0.5);
  material->set_static_friction(0.4);
  material->set_dynamic_friction(0.3);
  pb::SceneObject* probe = spec.add_objects();
  probe->set_name("probe");
  probe->set_kind(pb::OBJECT_KIND_TOOL);
  VectorToProto(Vector3d(0.02, 0.02, 0.02),
                probe->mutable_model()->mutable_procedural()->mutable_box()->mutable_size_m());
  VectorToProto(Vector3d(0.1, 0, 0.1), probe->mutable_pose()->mutable_position_m());
  return spec;
}

absl::StatusOr<pb::SceneSpec> LoadtestScene(const pb::SceneSpec& base, int clients,
                                            const std::string& name, bool tools_meet) {
  pb::SceneSpec spec = base;
  spec.set_name(name);
  spec.clear_objects();
  const pb::SceneObject* tool = nullptr;
  for (const pb::SceneObject& object : base.objects()) {
    if (object.kind() == pb::OBJECT_KIND_TOOL) {
      if (tool == nullptr) tool = &object;
    } else {
      *spec.add_objects() = object;
    }
  }
  if (tool == nullptr) return absl::InvalidArgumentError("the scene has no tool to copy");
  absl::StatusOr<Isometry3d> X_WT = PoseFromProto(tool->pose(), tool->name() + ".pose");
  if (!X_WT.ok()) return X_WT.status();
  const int groups = tools_meet ? (clients + 1) / 2 : clients;
  for (int i = 0; i < clients; ++i) {
    pb::SceneObject* copy = spec.add_objects();
    *copy = *tool;
    copy->set_name("tool-" + std::to_string(i));
    const int group = tools_meet ? i / 2 : i;
    const Isometry3d turn(Eigen::AngleAxisd(2 * M_PI * group / groups, Vector3d::UnitZ()));
    Isometry3d X_WC = *X_WT;
    if (tools_meet) X_WC.translation().y() += (i % 2 == 0 ? -0.5 : 0.5) * kMeetGapM;
    PoseToProto(turn * X_WC, copy->mutable_pose());
  }
  return spec;
}

std::vector<std::vector<TimedPose>> MeetingPaths(const std::vector<Isometry3d>& starts,
                                                 double rate_hz, double duration_s) {
  const size_t pairs = (starts.size() + 1) / 2;
  std::vector<std::vector<TimedPose>> paths;
  for (size_t i = 0; i < starts.size(); ++i) {
    MotionParams params;
    params.phase_s = static_cast<double>(i / 2) / static_cast<double>(pairs);
    const size_t partner = i ^ 1;
    if (partner < starts.size()) {
      const Vector3d apart = starts[partner].translation() - starts[i].translation();
      params.press_direction = apart.normalized();
      params.depth_m = 0.5 * apart.norm() + kMeetPastM;
    }
    paths.push_back(MotionPath(Motion::kPress, starts[i], rate_hz, duration_s, params));
  }
  return paths;
}

absl::StatusOr<std::vector<std::vector<TimedPose>>> DevicePaths(const pb::SceneSpec& spec,
                                                                int clients, bool tools_meet,
                                                                double rate_hz, double duration_s) {
  std::vector<Isometry3d> starts;
  for (int i = 0; i < clients; ++i) {
    absl::StatusOr<Isometry3d> X_WT =
        PoseFromProto(spec.objects(spec.objects_size() - clients + i).pose(), "tool pose");
    if (!X_WT.ok()) return X_WT.status();
    starts.push_back(*X_WT);
  }
  if (tools_meet) return MeetingPaths(starts, rate_hz, duration_s);
  std::vector<std::vector<TimedPose>> paths;
  for (int i = 0; i < clients; ++i) {
    MotionParams params;
    params.phase_s = static_cast<double>(i) / clients;
    paths.push_back(MotionPath(Motion::kPress, starts[i], rate_hz, duration_s, params));
  }
  return paths;
}

}  // namespace hs::cli

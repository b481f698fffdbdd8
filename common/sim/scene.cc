#include "common/sim/scene.h"

#include <algorithm>
#include <cmath>

#include "absl/strings/str_cat.h"
#include "common/core/rigid_pose.h"
#include "common/core/status_macros.h"
#include "common/sim/stage_timer.h"
#include "common/sim/tool_clashes.h"
#include "common/sim/tool_force.h"

namespace hs {
namespace {

// Collision models are grown for query tolerances up to this (relative).
constexpr double kMaxRelativeTolerance = 1e-6;
// A local model reaches at most this far, metres: its planes are searched
// for in the tool's box grown by it, so a larger one would take most of a
// scene's faces each step.
constexpr double kMaxLocalModelRadius = 1;

}  // namespace

absl::StatusOr<std::unique_ptr<Scene>> Scene::Create(const SceneOptions& options) {
  if (!(std::isfinite(options.step_s) && options.step_s > 0)) {
    return absl::InvalidArgumentError("step_s must be finite and > 0");
  }
  if (!(options.relative_tolerance >= 0 && options.relative_tolerance <= kMaxRelativeTolerance)) {
    return absl::InvalidArgumentError("relative_tolerance must be in [0, 1e-6]");
  }
  if (!(std::isfinite(options.force_clamp_n) && options.force_clamp_n > 0)) {
    return absl::InvalidArgumentError("force_clamp_n must be finite and > 0");
  }
  if (!(options.local_model_radius_m > 0 && options.local_model_radius_m <= kMaxLocalModelRadius)) {
    return absl::InvalidArgumentError("local_model_radius_m must be in (0, 1]");
  }
  if (!(options.local_model_radius_cap_m >= options.local_model_radius_m &&
        options.local_model_radius_cap_m <= kMaxLocalModelRadius)) {
    return absl::InvalidArgumentError(
        "local_model_radius_cap_m must be in [local_model_radius_m, 1]");
  }
  if (!(std::isfinite(options.contact_angular_damping_per_s) &&
        options.contact_angular_damping_per_s >= 0)) {
    return absl::InvalidArgumentError("contact_angular_damping_per_s must be finite and >= 0");
  }
  if (!options.gravity_W.allFinite()) {
    return absl::InvalidArgumentError("gravity_W must be finite");
  }
  if (!(options.parallel_work_share >= 0 && options.parallel_work_share <= 1)) {
    return absl::InvalidArgumentError("parallel_work_share must be in [0, 1]");
  }
  return std::unique_ptr<Scene>(new Scene(options));
}

absl::StatusOr<ObjectId> Scene::AddObject(HapticObject object, ObjectKind kind,
                                          const Isometry3d& X_WO, const BodyOptions& body) {
  HS_RETURN_IF_ERROR(ValidateRigidPose(X_WO, "object"));
  MassProperties mass;
  if (kind == ObjectKind::kFree) {
    HS_ASSIGN_OR_RETURN(mass, ComputeMassProperties(object, body.mass_kg, body.density_kg_per_m3));
    if (!body.v_W.allFinite() || !body.w_W.allFinite()) {
      return absl::InvalidArgumentError("free body velocities must be finite");
    }
  }
  const double margin = kMaxRelativeTolerance * object.bounding_box().diagonal().norm();
  CollisionModel model(object, options_.bv, margin);
  const ObjectId id = objects_.Add(std::move(object), std::move(model), kind, X_WO);
  if (kind == ObjectKind::kTool) tools_.Add(id, X_WO);
  if (kind == ObjectKind::kFree) bodies_.Add(id, mass, FreeBodyState{X_WO, body.v_W, body.w_W});
  return id;
}

absl::Status Scene::SetThreads(int threads, const std::function<void()>& on_worker_start) {
  if (threads < 1 || threads > 64) {
    return absl::InvalidArgumentError(absl::StrCat("threads: ", threads, " is outside [1, 64]"));
  }
  if (threads != workers_->threads() || on_worker_start) {
    workers_ = std::make_unique<WorkerPool>(threads, on_worker_start);
    workers_->set_serial_below(std::chrono::nanoseconds(
        static_cast<int64_t>(options_.parallel_work_share * options_.step_s * 1e9)));
  }
  return absl::OkStatus();
}

absl::Status Scene::CheckTool(ObjectId id) const {
  if (id < 0 || id >= objects_.size()) {
    return absl::NotFoundError(absl::StrCat("no object ", id));
  }
  if (objects_[id].kind != ObjectKind::kTool) {
    return absl::FailedPreconditionError(absl::StrCat("object ", id, " is not a tool"));
  }
  return absl::OkStatus();
}

absl::Status Scene::CheckDevicePose(ObjectId id, const Isometry3d& X_WD) const {
  HS_RETURN_IF_ERROR(CheckTool(id));
  return ValidateRigidPose(X_WD, "device");
}

absl::Status Scene::RequestLocalModel(ObjectId id) {
  HS_RETURN_IF_ERROR(CheckTool(id));
  tools_.RequestLocalModel(id);
  return absl::OkStatus();
}

absl::Status Scene::SetLocalModelRadius(ObjectId id, double radius_m) {
  HS_RETURN_IF_ERROR(CheckTool(id));
  if (!(std::isfinite(radius_m) && radius_m >= 0)) {
    return absl::InvalidArgumentError("validity_radius_m must be finite and >= 0");
  }
  tools_.SetLocalModelRadius(id, radius_m == 0 ? 0
                                               : std::clamp(radius_m, options_.local_model_radius_m,
                                                            options_.local_model_radius_cap_m));
  return absl::OkStatus();
}

absl::Status Scene::SetSurfaceOnly(ObjectId id, bool surface_only) {
  HS_RETURN_IF_ERROR(CheckTool(id));
  tools_.SetSurfaceOnly(id, surface_only);
  return absl::OkStatus();
}

absl::Status Scene::SetDevicePose(ObjectId id, const Isometry3d& X_WD) {
  HS_RETURN_IF_ERROR(CheckDevicePose(id, X_WD));
  tools_.SetDevicePose(id, X_WD);
  return absl::OkStatus();
}

absl::Status Scene::SeatDevice(ObjectId id, const Isometry3d& X_WD) {
  HS_RETURN_IF_ERROR(CheckDevicePose(id, X_WD));
  tools_.SeatDevice(id, X_WD);
  return absl::OkStatus();
}

const StepFrame& Scene::Step() {
  ++frame_.step;
  frame_.time_s = static_cast<double>(frame_.step) * options_.step_s;
  EffectSet stages = StagesToRun(options_.enabled, needed_);
  if (bodies_.empty()) stages = stages.Without(Effect::kFreeBodyMotion);
  // No device moved, no model is asked for and the same stages are: no
  // stage runs, and the frame is the last one (docs/simulation.md, Still
  // devices); tools that touch go on touching.
  if (!stages.Has(Effect::kFreeBodyMotion) && stages == last_stages_ && tools_.NothingToStep()) {
    frame_.stages_run = EffectSet();
    CountClashes(frame_.tools, options_.step_s, frame_.clashes);
    return frame_;
  }
  frame_.stages_run = stages;
  last_stages_ = stages;
  tools_.Step(stages, *workers_, frame_.tools, stats_);
  frame_.bodies.resize(bodies_.size());
  if (stages.Has(Effect::kFreeBodyMotion)) {
    StageTimer timer(stats_[static_cast<int>(Effect::kFreeBodyMotion)]);
    // After the tools: bodies meet them at the proxies of this step.
    bodies_.Step(tools_, frame_.bodies);
    if (stages.Has(Effect::kForce)) {
      for (ToolFrame& tool : frame_.tools) {
        const ToolForce force = WithPushReaction({tool.force_W, tool.torque_W, tool.force_clamped},
                                                 bodies_.PushImpulseOf(tool.tool), options_.step_s,
                                                 options_.force_clamp_n);
        tool.force_W = force.force_W;
        tool.force_clamped = force.clamped;
      }
    }
  }
  CountClashes(frame_.tools, options_.step_s, frame_.clashes);
  return frame_;
}

absl::Status ApplyLocalModelRequest(Scene& scene, ObjectId id, const LocalModelRequest& model) {
  // The radius first: refused, it leaves the tool as it was.
  HS_RETURN_IF_ERROR(scene.SetLocalModelRadius(id, model.validity_radius_m));
  if (model.stale) HS_RETURN_IF_ERROR(scene.RequestLocalModel(id));
  return scene.SetSurfaceOnly(id, model.surface_only);
}

}  // namespace hs

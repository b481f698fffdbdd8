#include "common/sim/scene.h"

#include <chrono>
#include <cmath>

#include "absl/strings/str_cat.h"
#include "common/core/rigid_pose.h"
#include "common/core/status_macros.h"

namespace hs {
namespace {

// Collision models are grown for query tolerances up to this (relative).
constexpr double kMaxRelativeTolerance = 1e-6;

// Adds the wall time of its scope to one stage's statistics.
class StageTimer {
 public:
  explicit StageTimer(StageStats& stats)
      : stats_(stats), start_(std::chrono::steady_clock::now()) {}
  ~StageTimer() {
    ++stats_.runs;
    stats_.total_ns += std::chrono::duration_cast<std::chrono::nanoseconds>(
                           std::chrono::steady_clock::now() - start_)
                           .count();
  }

 private:
  StageStats& stats_;
  std::chrono::steady_clock::time_point start_;
};

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
  return std::unique_ptr<Scene>(new Scene(options));
}

absl::StatusOr<ObjectId> Scene::AddObject(HapticObject object, ObjectKind kind,
                                          const Isometry3d& X_WO) {
  HS_RETURN_IF_ERROR(ValidateRigidPose(X_WO, "object"));
  const double margin = kMaxRelativeTolerance * object.bounding_box().diagonal().norm();
  CollisionModel model(object, options_.bv, margin);
  const auto id = static_cast<ObjectId>(objects_.size());
  objects_.push_back(
      std::make_unique<Object>(Object{std::move(object), std::move(model), kind, X_WO}));
  if (kind == ObjectKind::kTool) tools_.push_back(Tool{id, X_WO, X_WO, X_WO, true});
  if (kind == ObjectKind::kFixed) {
    obstacles_.push_back(Posed(*objects_.back(), X_WO));
    obstacle_ids_.push_back(id);
  }
  return id;
}

absl::Status Scene::SetDevicePose(ObjectId id, const Isometry3d& X_WD) {
  if (id < 0 || id >= static_cast<ObjectId>(objects_.size())) {
    return absl::NotFoundError(absl::StrCat("no object ", id));
  }
  if (objects_[id]->kind != ObjectKind::kTool) {
    return absl::FailedPreconditionError(absl::StrCat("object ", id, " is not a tool"));
  }
  HS_RETURN_IF_ERROR(ValidateRigidPose(X_WD, "device"));
  for (Tool& tool : tools_) {
    if (tool.id != id) continue;
    tool.moved = tool.moved || !X_WD.isApprox(tool.X_WD, 0.0);
    tool.X_WD = X_WD;
  }
  return absl::OkStatus();
}

const StepFrame& Scene::Step() {
  ++frame_.step;
  frame_.time_s = static_cast<double>(frame_.step) * options_.step_s;
  bool anything_moved = false;
  for (const Tool& tool : tools_) anything_moved = anything_moved || tool.moved;
  // Nothing moves: the contacts are those of the last step, so no stage runs.
  if (!anything_moved) {
    frame_.stages_run = EffectSet();
    return frame_;
  }
  // No object is free yet (ObjectKind has none), so free-body motion never runs.
  frame_.stages_run = StagesToRun(options_.enabled, needed_).Without(Effect::kFreeBodyMotion);
  frame_.tools.resize(tools_.size());
  for (size_t i = 0; i < tools_.size(); ++i) {
    StepTool(tools_[i], frame_.stages_run, frame_.tools[i]);
    tools_[i].X_WD_previous = tools_[i].X_WD;
    tools_[i].moved = false;
  }
  return frame_;
}

void Scene::StepTool(Tool& tool, EffectSet stages, ToolFrame& frame) {
  const Object& t = *objects_[tool.id];
  const Vector3d motion = tool.X_WD.translation() - tool.X_WD_previous.translation();
  const bool continuous = stages.Has(Effect::kContinuousCollision);
  frame.tool = tool.id;
  frame.X_WD = tool.X_WD;
  frame.X_WP = tool.X_WD;
  frame.force_W.setZero();
  frame.torque_W.setZero();
  frame.force_clamped = false;
  frame.contacts.clear();
  const PosedObject device = Posed(t, tool.X_WD);
  // Continuous collision and friction run inside the collision and proxy
  // stages: their runs are counted here, their time is their hosts'.
  if (continuous && stages.Has(Effect::kCollision)) {
    ++stats_[static_cast<int>(Effect::kContinuousCollision)].runs;
  }
  if (stages.Has(Effect::kFriction)) ++stats_[static_cast<int>(Effect::kFriction)].runs;

  if (stages.Has(Effect::kCollision)) {
    StageTimer timer(stats_[static_cast<int>(Effect::kCollision)]);
    for (size_t k = 0; k < obstacles_.size(); ++k) {
      const absl::StatusOr<bool> colliding =
          AreColliding(device, obstacles_[k], options_.relative_tolerance,
                       continuous ? std::optional<Vector3d>(motion) : std::nullopt);
      if (colliding.ok() && *colliding) {
        PairContact pair{obstacle_ids_[k], {}};
        pair.contact.colliding = true;
        frame.contacts.push_back(std::move(pair));
      }
    }
  }
  if (stages.Has(Effect::kContactSet)) {
    StageTimer timer(stats_[static_cast<int>(Effect::kContactSet)]);
    // D is the device's way in from its proxy, which the last step left
    // outside every object: reversing it ends at the surface the device
    // went through. The device's own motion is tangent to the surface while
    // it slides, and reversing that would travel far inside the object.
    const Vector3d from_proxy = tool.X_WD.translation() - tool.X_WP.translation();
    const ContactQuery at_device{.direction_W = from_proxy.squaredNorm() > 0 ? from_proxy : motion,
                                 .method = options_.method,
                                 .relative_tolerance = options_.relative_tolerance};
    // A device that passed through an object in this step (the collision
    // stage's swept query caught it) is reconstructed at its first touch
    // along the step; the swept query is not paid for when the device is in.
    ContactQuery along_step = at_device;
    along_step.direction_W = motion;
    along_step.continuous = true;
    for (PairContact& pair : frame.contacts) {
      const Object& o = *objects_[pair.object];
      absl::StatusOr<ContactSet> contact = ComputeContact(device, Posed(o, o.X_WO), at_device);
      if (continuous && contact.ok() && !contact->colliding) {
        contact = ComputeContact(device, Posed(o, o.X_WO), along_step);
      }
      if (contact.ok()) pair.contact = *contact;
    }
  }
  if (!stages.Has(Effect::kReversingVector)) {
    tool.X_WP = tool.X_WD;
    return;
  }
  ProxyState proxy;
  {
    StageTimer timer(stats_[static_cast<int>(Effect::kReversingVector)]);
    const ProxyOptions options{.relative_tolerance = options_.relative_tolerance,
                               .friction = stages.Has(Effect::kFriction)};
    absl::StatusOr<ProxyState> moved = MoveProxy(device, tool.X_WP, tool.X_WD, obstacles_, options);
    proxy = moved.ok() ? *moved : ProxyState{tool.X_WP};
    if (proxy.touching) proxy.obstacle = obstacle_ids_[proxy.obstacle];
    tool.X_WP = proxy.X_WP;
    frame.X_WP = proxy.X_WP;
  }
  if (stages.Has(Effect::kForce) && proxy.touching) {
    StageTimer timer(stats_[static_cast<int>(Effect::kForce)]);
    const Material& m = objects_[proxy.obstacle]->object.face_material(proxy.face);
    const Vector3d stretch = proxy.X_WP.translation() - tool.X_WD.translation();
    const Vector3d velocity = motion / options_.step_s;
    // Spring toward the proxy; damping of the device's speed along the normal.
    Vector3d force = m.stiffness_n_per_m * stretch -
                     m.damping_ns_per_m * velocity.dot(proxy.normal_W) * proxy.normal_W;
    if (force.norm() > options_.force_clamp_n) {
      force *= options_.force_clamp_n / force.norm();
      frame.force_clamped = true;
    }
    frame.force_W = force;
    frame.torque_W = (proxy.p_WC - proxy.X_WP.translation()).cross(force);
  }
}

}  // namespace hs

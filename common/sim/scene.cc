#include "common/sim/scene.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "absl/strings/str_cat.h"
#include "common/core/rigid_pose.h"
#include "common/core/status_macros.h"
#include "common/sim/touched_face.h"

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
  if (!(std::isfinite(options.contact_angular_damping_per_s) &&
        options.contact_angular_damping_per_s >= 0)) {
    return absl::InvalidArgumentError("contact_angular_damping_per_s must be finite and >= 0");
  }
  if (!options.gravity_W.allFinite()) {
    return absl::InvalidArgumentError("gravity_W must be finite");
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
  const auto id = static_cast<ObjectId>(objects_.size());
  smallest_edge_m_ = std::min(smallest_edge_m_, object.smallest_box_edge());
  objects_.push_back(
      std::make_unique<Object>(Object{std::move(object), std::move(model), kind, X_WO}));
  const Object& added = *objects_.back();
  switch (kind) {
    case ObjectKind::kTool:
      slots_.push_back(static_cast<int>(tools_.size()));
      tools_.push_back(Tool{id, X_WO, X_WO, X_WO, X_WO, true});
      return id;
    case ObjectKind::kFixed:
      slots_.push_back(-1);
      obstacles_.push_back(Posed(added, X_WO));
      obstacle_ids_.push_back(id);
      break;
    case ObjectKind::kFree:
      slots_.push_back(static_cast<int>(bodies_.size()));
      bodies_.push_back(Body{id, mass, FreeBodyState{X_WO, body.v_W, body.w_W}, X_WO});
      break;
  }
  targets_.push_back(Posed(added, X_WO));
  target_ids_.push_back(id);
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
  EffectSet stages = StagesToRun(options_.enabled, needed_);
  if (bodies_.empty()) stages = stages.Without(Effect::kFreeBodyMotion);
  bool anything_moved = stages.Has(Effect::kFreeBodyMotion);
  for (const Tool& tool : tools_) anything_moved = anything_moved || tool.moved;
  // Nothing moves: the contacts are those of the last step, so no stage runs.
  if (!anything_moved) {
    frame_.stages_run = EffectSet();
    return frame_;
  }
  frame_.stages_run = stages;
  frame_.tools.resize(tools_.size());
  for (size_t i = 0; i < tools_.size(); ++i) {
    tools_[i].X_WP_previous = tools_[i].X_WP;
    StepTool(tools_[i], frame_.stages_run, frame_.tools[i]);
    tools_[i].X_WD_previous = tools_[i].X_WD;
    tools_[i].moved = false;
  }
  frame_.bodies.resize(bodies_.size());
  if (stages.Has(Effect::kFreeBodyMotion)) {
    StageTimer timer(stats_[static_cast<int>(Effect::kFreeBodyMotion)]);
    for (Body& body : bodies_) body.X_WO_start = body.state.X_WO;
    // Serially, in id order: each body meets the others where they are now
    // (paper s.5), so a body moved earlier this step is met at its new pose.
    for (size_t i = 0; i < bodies_.size(); ++i) MoveFreeBody(bodies_[i], frame_.bodies[i]);
    for (size_t k = 0; k < targets_.size(); ++k) targets_[k].X_WO = objects_[target_ids_[k]]->X_WO;
  }
  return frame_;
}

void Scene::MoveFreeBody(Body& body, BodyFrame& frame) {
  frame.body = body.id;
  frame.contacts = 0;
  // Keep each sub-step's travel under the shortest box edge of any object
  // (paper s.4): the travel is estimated from the velocity after gravity.
  const double dt = options_.step_s;
  const double travel = (body.state.v_W + dt * options_.gravity_W).norm() * dt;
  constexpr int kMaxSubsteps = 64;
  frame.substeps = std::min(kMaxSubsteps, 1 + static_cast<int>(travel / smallest_edge_m_));
  const double h = dt / frame.substeps;
  for (int sub = 0; sub < frame.substeps; ++sub) {
    const Isometry3d X_WO_from = body.state.X_WO;
    IntegrateFreeBody(body.mass, options_.gravity_W, h, body.state);
    int touching = 0;
    for (ObjectId other = 0; other < static_cast<ObjectId>(objects_.size()); ++other) {
      if (other != body.id) touching += ResolveContact(body, X_WO_from, other);
    }
    if (touching > 0) body.state.w_W *= std::exp(-options_.contact_angular_damping_per_s * h);
    frame.contacts += touching;
  }
  objects_[body.id]->X_WO = body.state.X_WO;
  frame.X_WO = body.state.X_WO;
  frame.v_W = body.state.v_W;
  frame.w_W = body.state.w_W;
}

Scene::Counterpart Scene::CounterpartOf(ObjectId id) {
  const Object& o = *objects_[id];
  Counterpart c;
  c.X_WO = o.X_WO;
  switch (o.kind) {
    case ObjectKind::kFixed:
      break;
    case ObjectKind::kTool: {
      const Tool& tool = tools_[slots_[id]];
      c.X_WO = tool.X_WP;
      c.motion_W = tool.X_WP.translation() - tool.X_WP_previous.translation();
      c.v_W = c.motion_W / options_.step_s;
      break;
    }
    case ObjectKind::kFree: {
      Body& other = bodies_[slots_[id]];
      c.X_WO = other.state.X_WO;
      c.motion_W = other.state.X_WO.translation() - other.X_WO_start.translation();
      c.body = {&other.mass, &other.state};
      break;
    }
  }
  return c;
}

bool Scene::ResolveContact(Body& body, const Isometry3d& X_WO_from, ObjectId other) {
  const Object& self = *objects_[body.id];
  const Object& that = *objects_[other];
  const Counterpart c = CounterpartOf(other);
  // The body's motion relative to the other object: the direction the
  // reversing vector undoes.
  const ContactQuery query{
      .direction_W = body.state.X_WO.translation() - X_WO_from.translation() - c.motion_W,
      .method = options_.method,
      .relative_tolerance = options_.relative_tolerance};
  const absl::StatusOr<ContactSet> contact =
      ComputeContact(Posed(self, body.state.X_WO), Posed(that, c.X_WO), query);
  if (!contact.ok() || !contact->colliding || contact->normal_W.isZero()) return false;
  BodyContact response;
  response.normal_W = FaceSideNormal(that.object, contact->fixed, c.X_WO);
  if (response.normal_W.isZero()) response.normal_W = contact->normal_W;
  // The normal share of the reversing vector: moving back along the whole
  // vector would also undo the body's sliding along the surface.
  if (contact->penetrating) {
    response.separation_m = std::max(0.0, contact->reversing_vector_W.dot(response.normal_W));
  }
  response.p_WC = CentreOfMass(body.mass, body.state);
  if (!contact->points.empty()) {
    Vector3d sum = Vector3d::Zero();
    for (const ContactPoint& p : contact->points) sum += p.p_WC;
    response.p_WC = sum / static_cast<double>(contact->points.size());
  }
  response.v_other_W = c.v_W;
  response.friction =
      that.object.face_material(TouchedFace(that.object, contact->fixed)).dynamic_friction;
  RespondToContact(body.mass, response, body.state, c.body);
  return true;
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
    for (size_t k = 0; k < targets_.size(); ++k) {
      const absl::StatusOr<bool> colliding =
          AreColliding(device, targets_[k], options_.relative_tolerance,
                       continuous ? std::optional<Vector3d>(motion) : std::nullopt);
      if (colliding.ok() && *colliding) {
        PairContact pair{target_ids_[k], {}};
        pair.contact.colliding = true;
        frame.contacts.push_back(std::move(pair));
      }
    }
  }
  if (stages.Has(Effect::kContactSet)) {
    StageTimer timer(stats_[static_cast<int>(Effect::kContactSet)]);
    const ContactQuery query{.direction_W = motion,
                             .method = options_.method,
                             .continuous = continuous,
                             .relative_tolerance = options_.relative_tolerance};
    for (PairContact& pair : frame.contacts) {
      const Object& o = *objects_[pair.object];
      const absl::StatusOr<ContactSet> contact = ComputeContact(device, Posed(o, o.X_WO), query);
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

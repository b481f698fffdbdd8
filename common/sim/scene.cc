#include "common/sim/scene.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "absl/strings/str_cat.h"
#include "common/core/rigid_pose.h"
#include "common/core/status_macros.h"
#include "common/sim/motion_bounds.h"
#include "common/sim/tool_force.h"

namespace hs {
namespace {

// Collision models are grown for query tolerances up to this (relative).
constexpr double kMaxRelativeTolerance = 1e-6;
// A step is split into at most this many sub-steps: a tool moving farther
// than this many shortest box edges in one step may pass through.
constexpr int kMaxSubsteps = 256;

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
  broad_phase_.Add(id, added.model, X_WO);
  switch (kind) {
    case ObjectKind::kTool:
      slots_.push_back(static_cast<int>(tools_.size()));
      tools_.push_back(Tool{id, X_WO, X_WO, X_WO, X_WO, true});
      target_index_.push_back(-1);
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
  target_index_.push_back(static_cast<int>(targets_.size()));
  targets_.push_back(Posed(added, X_WO));
  target_ids_.push_back(id);
  target_boxes_.push_back(GrowBox(WorldBox(added.object, X_WO), added.model.margin_m()));
  return id;
}

absl::Status Scene::SetThreads(int threads, const std::function<void()>& on_worker_start) {
  if (threads < 1 || threads > 64) {
    return absl::InvalidArgumentError(absl::StrCat("threads: ", threads, " is outside [1, 64]"));
  }
  if (threads != workers_->threads() || on_worker_start) {
    workers_ = std::make_unique<WorkerPool>(threads, on_worker_start);
  }
  return absl::OkStatus();
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
  for (const Tool& tool : tools_) {
    if (tool.moved) broad_phase_.SetPose(tool.id, tool.X_WD);
  }
  // The broad phase's pairs at the device poses, for tools whose collision
  // stage is neither continuous nor sub-stepped (those take swept boxes).
  if (stages.Has(Effect::kCollision) && !stages.Has(Effect::kContinuousCollision) &&
      options_.broad_phase && !tools_.empty()) {
    broad_pairs_ = broad_phase_.CandidatePairs();
  }
  frame_.tools.resize(tools_.size());
  scratch_.resize(tools_.size());
  for (size_t i = 0; i < tools_.size(); ++i) {
    frame_.tools[i].tool = tools_[i].id;
    frame_.tools[i].X_WD = tools_[i].X_WD;
  }
  // Each tool's step is two halves that read the same state and write apart
  // (its contacts; its proxy and force), so they run at once too: a scene
  // of one tool uses a second core as well. A half with no stage to run
  // only clears its part of the frame, here, and takes no thread.
  const bool contacts = stages.Has(Effect::kCollision) || stages.Has(Effect::kContactSet);
  const bool proxy = stages.Has(Effect::kReversingVector);
  halves_.clear();
  for (int i = 0; i < static_cast<int>(tools_.size()); ++i) {
    for (const bool is_contacts : {true, false}) {
      if (is_contacts ? contacts : proxy) {
        halves_.push_back({i, is_contacts});
      } else {
        StepHalf({i, is_contacts}, stages);
      }
    }
  }
  workers_->ForEach(static_cast<int>(halves_.size()), [&](int k) { StepHalf(halves_[k], stages); });
  for (size_t i = 0; i < tools_.size(); ++i) {
    Tool& tool = tools_[i];
    tool.X_WP_previous = tool.X_WP;
    tool.X_WP = frame_.tools[i].X_WP;
    tool.X_WD_previous = tool.X_WD;
    tool.moved = false;
  }
  for (ToolScratch& scratch : scratch_) {
    for (const StageStatsTable* half : {&scratch.contact_stats, &scratch.proxy_stats}) {
      for (int e = 0; e < kNumEffects; ++e) {
        stats_[e].runs += (*half)[e].runs;
        stats_[e].total_ns += (*half)[e].total_ns;
      }
    }
    scratch.contact_stats = {};
    scratch.proxy_stats = {};
  }
  frame_.bodies.resize(bodies_.size());
  if (stages.Has(Effect::kFreeBodyMotion)) {
    StageTimer timer(stats_[static_cast<int>(Effect::kFreeBodyMotion)]);
    for (Body& body : bodies_) body.X_WO_start = body.state.X_WO;
    for (Tool& tool : tools_) tool.push_impulse_W.setZero();
    // Serially, in id order: each body meets the others where they are now
    // (paper s.5), so a body moved earlier this step is met at its new pose.
    for (size_t i = 0; i < bodies_.size(); ++i) MoveFreeBody(bodies_[i], frame_.bodies[i]);
    for (const Body& body : bodies_) {
      const Object& o = *objects_[body.id];
      const int k = target_index_[body.id];
      targets_[k].X_WO = o.X_WO;
      target_boxes_[k] = GrowBox(WorldBox(o.object, o.X_WO), o.model.margin_m());
      broad_phase_.SetPose(body.id, o.X_WO);
    }
    if (stages.Has(Effect::kForce)) {
      for (size_t i = 0; i < tools_.size(); ++i) AddPushReaction(tools_[i], frame_.tools[i]);
    }
  }
  return frame_;
}

void Scene::FindCandidates(const Tool& tool, Candidates which, ToolScratch& scratch) const {
  const HapticObject& t = objects_[tool.id]->object;
  std::vector<int>& candidates = scratch.candidates;
  candidates.clear();
  if (which != Candidates::kAtDevicePose) {
    const AlignedBox3d box =
        GrowBox(SweptBox(t, tool.X_WD_previous, tool.X_WD), objects_[tool.id]->model.margin_m());
    for (int k = 0; k < static_cast<int>(targets_.size()); ++k) {
      if (which == Candidates::kEvery || box.intersects(target_boxes_[k])) candidates.push_back(k);
    }
    return;
  }
  for (const auto& [a, b] : broad_pairs_) {
    if (a != tool.id && b != tool.id) continue;
    const int k = target_index_[a == tool.id ? b : a];
    if (k >= 0) candidates.push_back(k);
  }
  std::sort(candidates.begin(), candidates.end());
}

void Scene::FindProxyObstacles(const Tool& tool, ToolScratch& scratch) const {
  scratch.proxy_obstacles.clear();
  scratch.proxy_obstacle_ids.clear();
  const Object& t = *objects_[tool.id];
  // The proxy only moves toward the device: every pose it takes lies within
  // the device's distance of the device pose (plus a stand-off per slide,
  // far under the margin added here).
  const double reach = (tool.X_WD.translation() - tool.X_WP.translation()).norm() +
                       1e-5 * t.object.bounding_box().diagonal().norm() + t.model.margin_m();
  const AlignedBox3d box = GrowBox(WorldBox(t.object, tool.X_WD), reach);
  for (size_t k = 0; k < obstacles_.size(); ++k) {
    const ObjectId id = obstacle_ids_[k];
    if (options_.broad_phase && !box.intersects(target_boxes_[target_index_[id]])) continue;
    scratch.proxy_obstacles.push_back(obstacles_[k]);
    scratch.proxy_obstacle_ids.push_back(id);
  }
}

void Scene::FindToolContacts(const Tool& tool, bool continuous, ToolFrame& frame,
                             ToolScratch& scratch) const {
  const Object& t = *objects_[tool.id];
  const Isometry3d& from = tool.X_WD_previous;
  const Isometry3d& to = tool.X_WD;
  // Without continuous collision, a step longer than the shortest box edge
  // of the objects it may meet is split so that none is passed through
  // (paper s.4, fig. 3 c). Which objects it may meet: the swept boxes.
  if (!continuous) {
    FindCandidates(tool, Candidates::kSwept, scratch);
    double edge = t.object.smallest_box_edge();
    for (const int k : scratch.candidates)
      edge = std::min(edge, targets_[k].object->smallest_box_edge());
    frame.substeps = SubstepCount(Travel(t.object, from, to), edge, kMaxSubsteps);
  }
  const bool swept = continuous || frame.substeps > 1;
  const Candidates which = !options_.broad_phase ? Candidates::kEvery
                           : swept               ? Candidates::kSwept
                                                 : Candidates::kAtDevicePose;
  if (continuous || which != Candidates::kSwept) FindCandidates(tool, which, scratch);
  const Vector3d motion = to.translation() - from.translation();
  const PosedObject device = Posed(t, to);
  for (const int k : scratch.candidates) {
    int substep = frame.substeps;
    auto colliding_at = [&](const PosedObject& moving) {
      const absl::StatusOr<bool> colliding =
          AreColliding(moving, targets_[k], options_.relative_tolerance,
                       continuous ? std::optional<Vector3d>(motion) : std::nullopt);
      return colliding.ok() && *colliding;
    };
    // At the device pose first; if not there, at the first sub-step that touches.
    bool found = colliding_at(device);
    for (int i = 1; !found && i < frame.substeps; ++i) {
      found = colliding_at(
          Posed(t, InterpolatePose(from, to, static_cast<double>(i) / frame.substeps)));
      substep = i;
    }
    if (!found) continue;
    PairContact& pair = frame.contacts.emplace_back();
    pair.object = target_ids_[k];
    pair.substep = substep;
    pair.contact = ContactSet{};
    pair.contact.colliding = true;
  }
}

void Scene::StepHalf(ToolHalf half, EffectSet stages) {
  if (half.contacts) {
    StepToolContacts(tools_[half.tool], stages, frame_.tools[half.tool], scratch_[half.tool]);
  } else {
    StepToolProxy(tools_[half.tool], stages, frame_.tools[half.tool], scratch_[half.tool]);
  }
}

void Scene::StepToolContacts(const Tool& tool, EffectSet stages, ToolFrame& frame,
                             ToolScratch& scratch) const {
  const Object& t = *objects_[tool.id];
  const Vector3d motion = tool.X_WD.translation() - tool.X_WD_previous.translation();
  const bool continuous = stages.Has(Effect::kContinuousCollision);
  StageStatsTable& stats = scratch.contact_stats;
  frame.contacts.clear();
  frame.substeps = 1;
  // Continuous collision runs inside the collision stage: its runs are
  // counted here, its time is the collision stage's.
  if (continuous && stages.Has(Effect::kCollision)) {
    ++stats[static_cast<int>(Effect::kContinuousCollision)].runs;
  }
  if (stages.Has(Effect::kCollision)) {
    StageTimer timer(stats[static_cast<int>(Effect::kCollision)]);
    FindToolContacts(tool, continuous, frame, scratch);
  }
  if (!stages.Has(Effect::kContactSet)) return;
  StageTimer timer(stats[static_cast<int>(Effect::kContactSet)]);
  const PosedObject device = Posed(t, tool.X_WD);
  // D is the device's way in from its proxy, which the last step left
  // outside every object: reversing it ends at the surface the device
  // went through. The device's own motion is tangent to the surface while
  // it slides, and reversing that would travel far inside the object.
  const Vector3d from_proxy = tool.X_WD.translation() - tool.X_WP.translation();
  // The proxy stood outside at its distance from the device: the exact
  // method searches that far at once.
  const ContactQuery at_device{.direction_W = from_proxy.squaredNorm() > 0 ? from_proxy : motion,
                               .method = options_.method,
                               .relative_tolerance = options_.relative_tolerance,
                               .depth_hint_m = from_proxy.norm()};
  // A device that passed through an object in this step (the collision
  // stage's swept query caught it) is reconstructed at its first touch
  // along the step; the swept query is not paid for when the device is in.
  ContactQuery along_motion = at_device;
  along_motion.direction_W = motion;
  along_motion.depth_hint_m = 0;
  ContactQuery along_step = along_motion;
  along_step.continuous = true;
  for (PairContact& pair : frame.contacts) {
    const Object& o = *objects_[pair.object];
    // A pair found at an earlier sub-step is reported at that sub-step's
    // pose, along the motion: the tool passed through and no longer
    // touches at the end.
    const bool at_end = pair.substep == frame.substeps;
    const PosedObject at =
        at_end ? device
               : Posed(t, InterpolatePose(tool.X_WD_previous, tool.X_WD,
                                          static_cast<double>(pair.substep) / frame.substeps));
    absl::StatusOr<ContactSet> contact =
        ComputeContact(at, Posed(o, o.X_WO), at_end ? at_device : along_motion);
    if (continuous && contact.ok() && !contact->colliding) {
      contact = ComputeContact(device, Posed(o, o.X_WO), along_step);
    }
    if (contact.ok()) pair.contact = *std::move(contact);
  }
}

void Scene::StepToolProxy(const Tool& tool, EffectSet stages, ToolFrame& frame,
                          ToolScratch& scratch) const {
  const Object& t = *objects_[tool.id];
  const Vector3d motion = tool.X_WD.translation() - tool.X_WD_previous.translation();
  StageStatsTable& stats = scratch.proxy_stats;
  frame.X_WP = tool.X_WD;
  frame.force_W.setZero();
  frame.torque_W.setZero();
  frame.force_clamped = false;
  // Friction runs inside the proxy stage: its runs are counted here, its
  // time is the proxy's.
  if (stages.Has(Effect::kFriction)) ++stats[static_cast<int>(Effect::kFriction)].runs;
  if (!stages.Has(Effect::kReversingVector)) return;
  ProxyState proxy;
  {
    StageTimer timer(stats[static_cast<int>(Effect::kReversingVector)]);
    const ProxyOptions options{.relative_tolerance = options_.relative_tolerance,
                               .friction = stages.Has(Effect::kFriction)};
    FindProxyObstacles(tool, scratch);
    absl::StatusOr<ProxyState> moved =
        MoveProxy(Posed(t, tool.X_WD), tool.X_WP, tool.X_WD, scratch.proxy_obstacles, options);
    proxy = moved.ok() ? *moved : ProxyState{tool.X_WP};
    if (proxy.touching) proxy.obstacle = scratch.proxy_obstacle_ids[proxy.obstacle];
    frame.X_WP = proxy.X_WP;
  }
  if (stages.Has(Effect::kForce) && proxy.touching) {
    StageTimer timer(stats[static_cast<int>(Effect::kForce)]);
    const ToolForce force =
        SpringDamperForce(objects_[proxy.obstacle]->object.face_material(proxy.face),
                          ToolContact{.p_WD = tool.X_WD.translation(),
                                      .p_WP = proxy.X_WP.translation(),
                                      .v_WD = motion / options_.step_s,
                                      .normal_W = proxy.normal_W,
                                      .p_WC = proxy.p_WC},
                          options_.force_clamp_n);
    frame.force_W = force.force_W;
    frame.torque_W = force.torque_W;
    frame.force_clamped = force.clamped;
  }
}

}  // namespace hs

#include "common/sim/tool_stage.h"

#include <algorithm>

#include "common/sim/frame_storage.h"
#include "common/sim/local_model_anchor.h"
#include "common/sim/local_model_builder.h"
#include "common/sim/motion_bounds.h"
#include "common/sim/proxy.h"
#include "common/sim/stage_timer.h"
#include "common/sim/tool_force.h"

namespace hs {
namespace {

// A step is split into at most this many sub-steps: a tool moving farther
// than this many shortest box edges in one step may pass through.
constexpr int kMaxSubsteps = 256;

// A face search gathers the pairs of features that may give a plane while
// the proxy moves by this fraction of the validity radius; each model is
// made from them, as a search there would, until the proxy has moved
// farther or the search is older than the period below (which no
// correctness needs: the fixed objects do not move, and a scene edit makes
// a new scene). 0.1 to 0.15 cost least (docs/benchmarks.md).
//
// A touching proxy that did not turn gets no margin: it is given a new
// model only when it has slid past kAnchorMoveFraction of the radius
// (below), or off its model's planes, and pairs with a margin, dearer to
// gather and to make models from, served few of those models
// (step_bench's remote_device, 2026-11-30: docs/benchmarks.md).
constexpr double kPairMarginFraction = 0.15;
// How far ahead of the proxy a search is made, as a fraction of the
// margin: the proxy must stay within the margin of that pose.
constexpr double kAheadFraction = 0.9;
constexpr double kLongestSearchPeriodS = 1.0;

// A model holds for every point within its validity radius of the proxy it
// was taken at, and a device's loop keeps its own proxy within that radius
// of it: a proxy in free space that has moved by less than this fraction
// of the radius is served by the last model, which leaves the device nine
// tenths of it.
// The period bounds how long a device's loop goes without the server's
// correction of its proxy's drift (client/haptic_loop), a proxy held still
// on a surface included. What holding saves: docs/benchmarks.md.
constexpr double kModelMoveFraction = 0.1;
constexpr double kLongestModelPeriodS = 0.05;
// A touching proxy that has slid by less than this fraction of the radius
// since the last model built gets that model anchored where it is
// (local_model_anchor.h): the same planes, a radius less by the slide.
constexpr double kAnchorMoveFraction = 0.25;

// The contact ProxiesPenetrate reconstructs, kept from step to step.
struct StartContact {
  ContactSet contact;
};

// How far a face search gathers pairs (LocalModelPairs::complete_m), given
// the model the last one made: the whole radius unless that model was
// full, else twice the gap of its farthest plane with the margin, which a
// proxy's move within the margin does not take the farthest plane past.
// A touching proxy searched without a margin may have slid farther since
// that model (a quarter of the radius); where the new model's farthest
// plane lies beyond the reach, ModelFromPairs says so and the step
// searches the whole radius (no step_bench path did, 2026-11-30).
// A shorter search has fewer pairs to find and each step fewer to test.
double SearchReach(const LocalModel& last, const LocalModelOptions& options, double margin_m) {
  if (last.revision == 0 || static_cast<int>(last.planes.size()) < options.max_planes) {
    return options.radius_m;
  }
  return std::min(options.radius_m, 2 * (last.planes.back().gap_m + margin_m));
}

// Whether `last` says what a model at `proxy` with `options` must no more,
// whatever the proxy did: it was made with other options or another touch,
// or is older than the longest period. Both kinds of model are renewed so.
bool ModelOutdated(const LocalModel& last, const ProxyState& proxy,
                   const LocalModelOptions& options, int steps_since_model, double step_s) {
  return last.validity_radius_m != options.radius_m || last.friction != options.friction ||
         last.force_clamp_n != options.force_clamp_n || last.touching != proxy.touching ||
         steps_since_model * step_s > kLongestModelPeriodS;
}

// Whether a tool whose device reads the surface alone needs a new model
// beside `last` (no planes): what the model tells besides the surface
// changed. That is the proxy, for a touching proxy that slid (where the
// tool touches, the torque's lever, goes with it, as an anchored model's
// does) or one in free space that moved kModelMoveFraction of the radius;
// or the model is outdated.
bool SurfaceModelStale(const LocalModel& last, const ProxyState& proxy,
                       const LocalModelOptions& options, int steps_since_model, double step_s) {
  if (last.revision == 0 || !last.planes.empty() ||
      ModelOutdated(last, proxy, options, steps_since_model, step_s)) {
    return true;
  }
  if (proxy.touching) return !proxy.X_WP.isApprox(last.X_WP, 0.0);
  return (proxy.X_WP.translation() - last.X_WP.translation()).norm() >
         kModelMoveFraction * options.radius_m;
}

// The next model, after `model`, of a device that reads the surface alone.
void SurfaceOnlyModel(const ProxyState& proxy, const Vector3d& p_WD,
                      const LocalModelOptions& options,
                      const std::shared_ptr<const ModelSurface>& surface, LocalModel& model) {
  SetModelState(proxy, p_WD, options, model);
  model.planes.clear();
  model.surface = surface;
  ++model.revision;
}

void AddStats(StageStatsTable& to, StageStatsTable& from) {
  for (int e = 0; e < kNumEffects; ++e) {
    to[e].runs += from[e].runs;
    to[e].total_ns += from[e].total_ns;
  }
  from = {};
}

}  // namespace

void ToolStage::Add(ObjectId id, const Isometry3d& X_WO) {
  if (static_cast<int>(index_.size()) <= id) index_.resize(id + 1, -1);
  index_[id] = static_cast<int>(tools_.size());
  tools_.push_back(Tool{.id = id,
                        .X_WD_previous = X_WO,
                        .X_WD = X_WO,
                        .X_WP = X_WO,
                        .X_WP_previous = X_WO,
                        .X_WO_home = X_WO});
  scratch_.emplace_back();
}

void ToolStage::SetDevicePose(ObjectId id, const Isometry3d& X_WD) {
  Tool& tool = tools_[index_[id]];
  tool.moved = tool.moved || !X_WD.isApprox(tool.X_WD, 0.0);
  tool.X_WD = X_WD;
}

void ToolStage::SeatDevice(ObjectId id, const Isometry3d& X_WD) {
  Tool& tool = tools_[index_[id]];
  tool.moved = true;
  tool.seated = true;
  tool.X_WD = X_WD;
  tool.X_WD_previous = X_WD;
  tool.X_WP = tool.X_WO_home;
}

bool ToolStage::NothingToStep() const {
  if (!SameObstacles()) return false;
  for (size_t i = 0; i < tools_.size(); ++i) {
    if (tools_[i].moved || tools_[i].sliding || scratch_[i].model_wanted) return false;
  }
  return true;
}

void ToolStage::RequestLocalModel(ObjectId id) { scratch_[index_[id]].model_wanted = true; }

void ToolStage::SetLocalModelRadius(ObjectId id, double radius_m) {
  scratch_[index_[id]].model_radius_m = radius_m;
}

void ToolStage::SetSurfaceOnly(ObjectId id, bool surface_only) {
  ToolScratch& scratch = scratch_[index_[id]];
  // A model of the other kind at the next step: the last built one may be
  // of long ago.
  if (scratch.surface_only != surface_only) scratch.model_wanted = true;
  scratch.surface_only = surface_only;
}

ToolStage::ModelUpdate ToolStage::ModelUpdateFor(const ProxyState& proxy,
                                                 const LocalModelOptions& options,
                                                 ToolScratch& scratch) const {
  const LocalModel& built = scratch.built_model;
  if (scratch.model.revision == 0 || scratch.model_wanted ||
      scratch.model_pairs.obstacle_count != objects_.obstacles().size() ||
      ModelOutdated(built, proxy, options, ++scratch.steps_since_model, options_.step_s)) {
    return ModelUpdate::kBuild;
  }
  const double moved = MovedBy(built.X_WP, proxy.X_WP, scratch.model_pairs.lever_m);
  if (!proxy.touching) {
    return moved <= kModelMoveFraction * options.radius_m ? ModelUpdate::kKeep
                                                          : ModelUpdate::kBuild;
  }
  // In contact the proxy slides along the faces the planes stand for: the
  // point it touches (the torque's lever) and the drift a device's loop
  // corrects change with each move, so a touching proxy that moved gets
  // the last model anchored where it is now; one held still by the
  // surface keeps its own.
  if (proxy.X_WP.isApprox(scratch.model.X_WP, 0.0)) return ModelUpdate::kKeep;
  return moved <= kAnchorMoveFraction * options.radius_m ? ModelUpdate::kAnchor
                                                         : ModelUpdate::kBuild;
}

bool ToolStage::PairsServe(const Isometry3d& X_WP, ToolScratch& scratch) const {
  const LocalModelPairs& pairs = scratch.model_pairs;
  if (pairs.margin_m < 0 || scratch.model_wanted) return false;
  if (scratch.searched_radius_m != scratch.model_radius_m) return false;
  if (pairs.obstacle_count != objects_.obstacles().size()) return false;
  if (++scratch.steps_since_search * options_.step_s > kLongestSearchPeriodS) return false;
  return pairs.Moved(X_WP) <= pairs.margin_m;
}

ToolStage::ProxyMotion ToolStage::ProxyMotionOf(ObjectId id) const {
  const Tool& tool = tools_[index_[id]];
  return {tool.X_WP, tool.X_WP.translation() - tool.X_WP_previous.translation()};
}

void ToolStage::Step(EffectSet stages, WorkerPool& workers, std::vector<ToolFrame>& frames,
                     StageStatsTable& stats) {
  for (const Tool& tool : tools_) {
    if (tool.moved) objects_.PoseTool(tool.id, tool.X_WD);
  }
  // The broad phase's pairs at the device poses, for tools whose collision
  // stage is neither continuous nor sub-stepped (those take swept boxes).
  if (stages.Has(Effect::kCollision) && !stages.Has(Effect::kContinuousCollision) &&
      options_.broad_phase && !tools_.empty()) {
    objects_.FindCandidatePairs(broad_pairs_);
  }
  frames.resize(tools_.size());
  for (size_t i = 0; i < tools_.size(); ++i) {
    frames[i].tool = tools_[i].id;
    frames[i].X_WD = tools_[i].X_WD;
  }
  // Each tool's step is two halves that read the same state and write apart
  // (its contacts; its proxy and force), so they run at once too: a scene
  // of one tool uses a second core as well. The proxy halves of tools that
  // may meet run one after the other as one job (an island). A half with
  // no stage to run only clears its part of the frame, here, and takes no
  // thread.
  const bool contacts = stages.Has(Effect::kCollision) || stages.Has(Effect::kContactSet);
  const bool proxy = stages.Has(Effect::kReversingVector);
  if (proxy) GroupIslands(stages);
  jobs_.clear();
  for (int i = 0; i < static_cast<int>(tools_.size()); ++i) {
    if (!proxy) tools_[i].held = tools_[i].alone = false;
    scratch_[i].X_WP_now = tools_[i].X_WP;
    if (tools_[i].held) continue;
    if (contacts) {
      jobs_.push_back({i, true});
    } else {
      RunJob({i, true}, stages, frames);
    }
    if (!proxy) StepProxy(i, {}, stages, frames[i], scratch_[i]);
  }
  if (proxy) {
    for (int k = 0; k < islands_.size(); ++k) {
      if (!tools_[islands_.island(k).front()].held) jobs_.push_back({k, false});
    }
  }
  workers.ForEach(static_cast<int>(jobs_.size()), [&](int k) { RunJob(jobs_[k], stages, frames); });
  if (stages.Has(Effect::kForce)) AddToolReactions(frames);
  for (size_t i = 0; i < tools_.size(); ++i) {
    Tool& tool = tools_[i];
    // A seated proxy came from the home pose: free bodies meet no motion.
    tool.X_WP_previous = tool.seated ? frames[i].X_WP : tool.X_WP;
    // A proxy that reached its device, or moved less than the stand-off
    // its god object keeps off a surface (proxy.cc), rests: what is left
    // is the creep of standing off a curved surface, nanometres a step.
    const double stand_off = 1e-6 * objects_[tool.id].object.bounding_box().diagonal().norm();
    const Vector3d& p_WP = frames[i].X_WP.translation();
    tool.sliding = (p_WP - tool.X_WP.translation()).norm() > stand_off &&
                   (p_WP - tool.X_WD.translation()).norm() > stand_off;
    tool.X_WP = frames[i].X_WP;
    tool.X_WD_previous = tool.X_WD;
    tool.moved = false;
    tool.seated = false;
    AddStats(stats, scratch_[i].contact_stats);
    AddStats(stats, scratch_[i].proxy_stats);
  }
  last_stages_ = stages;
  last_obstacle_count_ = objects_.obstacles().size();
}

void ToolStage::GroupIslands(EffectSet stages) {
  reach_boxes_.resize(tools_.size());
  for (size_t i = 0; i < tools_.size(); ++i) {
    const Tool& tool = tools_[i];
    const SceneObjects::Object& t = objects_[tool.id];
    // The proxy only moves toward the device: every pose it takes lies
    // within the device's distance of the device pose (plus a stand-off
    // per slide, far under the margin added here).
    const double reach = (tool.X_WD.translation() - tool.X_WP.translation()).norm() +
                         1e-5 * t.object.bounding_box().diagonal().norm() + t.model.margin_m();
    reach_boxes_[i] = GrowBox(WorldBox(t.object, tool.X_WD), reach);
  }
  islands_.Group(reach_boxes_);
  for (int k = 0; k < islands_.size(); ++k) {
    const std::span<const int> island = islands_.island(k);
    for (const int i : island) {
      const bool alone = island.size() == 1;
      tools_[i].held = Holds(i, stages, alone);
      tools_[i].alone = alone;
    }
  }
}

bool ToolStage::Holds(int index, EffectSet stages, bool alone) const {
  const Tool& tool = tools_[index];
  return alone && tool.alone && !tool.moved && !tool.sliding && !tool.seated &&
         !scratch_[index].model_wanted && stages == last_stages_ &&
         !stages.Has(Effect::kFreeBodyMotion) && SameObstacles();
}

bool ToolStage::SameObstacles() const {
  return objects_.obstacles().size() == last_obstacle_count_;
}

void ToolStage::RunJob(StepJob job, EffectSet stages, std::vector<ToolFrame>& frames) {
  if (!job.contacts) {
    StepIsland(islands_.island(job.index), stages, frames);
    return;
  }
  ToolScratch& scratch = scratch_[job.index];
  const ScratchScope scope(scratch.contacts_space);
  StepContacts(tools_[job.index], stages, frames[job.index], scratch);
}

void ToolStage::StepIsland(std::span<const int> island, EffectSet stages,
                           std::vector<ToolFrame>& frames) {
  for (const int i : island) {
    ToolScratch& scratch = scratch_[i];
    const ScratchScope scope(scratch.proxy_space);
    StepProxy(i, island, stages, frames[i], scratch);
    scratch.X_WP_now = frames[i].X_WP;
  }
}

void ToolStage::AddToolReactions(std::vector<ToolFrame>& frames) {
  for (size_t i = 0; i < tools_.size(); ++i) {
    const ToolScratch& pusher = scratch_[i];
    if (pusher.touched_tool < 0) continue;
    ToolFrame& pushed = frames[index_[pusher.touched_tool]];
    // The pushed tool takes the force turned round at the touching point,
    // its torque about its own origin (tool_force.h).
    const Vector3d force_W = -pusher.force_from_tool.force_W;
    const ToolForce force = WithReaction(
        {pushed.force_W, pushed.torque_W, pushed.force_clamped},
        {.force_W = force_W, .torque_W = (pusher.p_WC - pushed.X_WP.translation()).cross(force_W)},
        options_.force_clamp_n);
    pushed.force_W = force.force_W;
    pushed.torque_W = force.torque_W;
    pushed.force_clamped = force.clamped;
  }
}

void ToolStage::FindCandidates(const Tool& tool, Candidates which, ToolScratch& scratch) const {
  std::vector<int>& candidates = scratch.candidates;
  candidates.clear();
  if (which != Candidates::kAtDevicePose) {
    const SceneObjects::Object& t = objects_[tool.id];
    const AlignedBox3d box =
        GrowBox(SweptBox(t.object, tool.X_WD_previous, tool.X_WD), t.model.margin_m());
    const std::vector<AlignedBox3d>& boxes = objects_.target_boxes();
    for (int k = 0; k < static_cast<int>(boxes.size()); ++k) {
      if (which == Candidates::kEvery || box.intersects(boxes[k])) candidates.push_back(k);
    }
    return;
  }
  for (const auto& [a, b] : broad_pairs_) {
    if (a != tool.id && b != tool.id) continue;
    const int k = objects_.target_index(a == tool.id ? b : a);
    if (k >= 0) candidates.push_back(k);
  }
  std::sort(candidates.begin(), candidates.end());
}

void ToolStage::FindProxyObstacles(int index, std::span<const int> island,
                                   ToolScratch& scratch) const {
  scratch.proxy_obstacles.clear();
  scratch.proxy_obstacle_ids.clear();
  const AlignedBox3d& box = reach_boxes_[index];
  const std::vector<ObjectId>& ids = objects_.obstacle_ids();
  for (size_t k = 0; k < ids.size(); ++k) {
    if (options_.broad_phase &&
        !box.intersects(objects_.target_boxes()[objects_.target_index(ids[k])])) {
      continue;
    }
    scratch.proxy_obstacles.push_back(objects_.obstacles()[k]);
    scratch.proxy_obstacle_ids.push_back(ids[k]);
  }
  for (const int other : island) {
    const ObjectId id = tools_[other].id;
    const Isometry3d& X_WP = scratch_[other].X_WP_now;
    if (other == index || !box.intersects(objects_.GrownBox(id, X_WP)) ||
        ProxiesPenetrate(index, other)) {
      continue;
    }
    scratch.proxy_obstacles.push_back(objects_.Posed(id, X_WP));
    scratch.proxy_obstacle_ids.push_back(id);
  }
}

bool ToolStage::ProxiesPenetrate(int index, int other) const {
  const Tool& tool = tools_[index];
  Isometry3d X_start = tool.X_WD;  // the device's orientation, where the proxy is
  X_start.translation() = tool.X_WP.translation();
  const PosedObject moving = objects_.Posed(tool.id, X_start);
  const PosedObject fixed = objects_.Posed(tools_[other].id, scratch_[other].X_WP_now);
  const absl::StatusOr<bool> colliding = AreColliding(moving, fixed, options_.relative_tolerance);
  // Proxies that touched last step stand off each other: only a device
  // seated into another tool, or tools placed touching, start in touch.
  if (colliding.ok() && !*colliding) return false;
  ContactSet& contact = Scratch<StartContact>().contact;
  const absl::Status status =
      ComputeContact(moving, fixed,
                     {.direction_W = X_start * moving.object->bounding_box().center() -
                                     fixed.X_WO * fixed.object->bounding_box().center(),
                      .relative_tolerance = options_.relative_tolerance},
                     contact);
  return !status.ok() || contact.penetrating;
}

void ToolStage::FindToolContacts(const Tool& tool, ToolFrame& frame, ToolScratch& scratch) const {
  const AlignedBox3d box = objects_.GrownBox(tool.id, tool.X_WD);
  const PosedObject device = objects_.Posed(tool.id, tool.X_WD);
  bool added = false;
  for (const Tool& other : tools_) {
    if (other.id == tool.id || !box.intersects(objects_.GrownBox(other.id, other.X_WD))) continue;
    const absl::StatusOr<bool> colliding =
        AreColliding(device, objects_.Posed(other.id, other.X_WD), options_.relative_tolerance);
    if (!colliding.ok() || !*colliding) continue;
    PairContact& pair = AddPairContact(frame.contacts, scratch.spare_contacts);
    pair.object = other.id;
    pair.substep = frame.substeps;
    pair.contact.colliding = true;
    added = true;
  }
  // One entry per object, by id, as ToolFrame::contacts promises.
  if (added) {
    std::sort(frame.contacts.begin(), frame.contacts.end(),
              [](const PairContact& x, const PairContact& y) { return x.object < y.object; });
  }
}

void ToolStage::FindContacts(const Tool& tool, bool continuous, ToolFrame& frame,
                             ToolScratch& scratch) const {
  const HapticObject& t = objects_[tool.id].object;
  const std::vector<PosedObject>& targets = objects_.targets();
  const Isometry3d& from = tool.X_WD_previous;
  const Isometry3d& to = tool.X_WD;
  // Without continuous collision, a step longer than the shortest box edge
  // of the objects it may meet is split so that none is passed through
  // (paper s.4, fig. 3 c). Which objects it may meet: the swept boxes.
  if (!continuous) {
    FindCandidates(tool, Candidates::kSwept, scratch);
    double edge = t.smallest_box_edge();
    for (const int k : scratch.candidates)
      edge = std::min(edge, targets[k].object->smallest_box_edge());
    frame.substeps = SubstepCount(Travel(t, from, to), edge, kMaxSubsteps);
  }
  const bool swept = continuous || frame.substeps > 1;
  const Candidates which = !options_.broad_phase ? Candidates::kEvery
                           : swept               ? Candidates::kSwept
                                                 : Candidates::kAtDevicePose;
  if (continuous || which != Candidates::kSwept) FindCandidates(tool, which, scratch);
  const Vector3d motion = to.translation() - from.translation();
  const PosedObject device = objects_.Posed(tool.id, to);
  for (const int k : scratch.candidates) {
    int substep = frame.substeps;
    auto colliding_at = [&](const PosedObject& moving) {
      const absl::StatusOr<bool> colliding =
          AreColliding(moving, targets[k], options_.relative_tolerance,
                       continuous ? std::optional<Vector3d>(motion) : std::nullopt);
      return colliding.ok() && *colliding;
    };
    // At the device pose first; if not there, at the first sub-step that touches.
    bool found = colliding_at(device);
    for (int i = 1; !found && i < frame.substeps; ++i) {
      found = colliding_at(objects_.Posed(
          tool.id, InterpolatePose(from, to, static_cast<double>(i) / frame.substeps)));
      substep = i;
    }
    if (!found) continue;
    PairContact& pair = AddPairContact(frame.contacts, scratch.spare_contacts);
    pair.object = objects_.target_ids()[k];
    pair.substep = substep;
    pair.contact.colliding = true;
  }
  FindToolContacts(tool, frame, scratch);
}

void ToolStage::StepContacts(const Tool& tool, EffectSet stages, ToolFrame& frame,
                             ToolScratch& scratch) const {
  const Vector3d motion = tool.X_WD.translation() - tool.X_WD_previous.translation();
  const bool continuous = stages.Has(Effect::kContinuousCollision);
  StageStatsTable& stats = scratch.contact_stats;
  ClearPairContacts(frame.contacts, scratch.spare_contacts);
  frame.substeps = 1;
  // Continuous collision runs inside the collision stage: its runs are
  // counted here, its time is the collision stage's.
  if (continuous && stages.Has(Effect::kCollision)) {
    ++stats[static_cast<int>(Effect::kContinuousCollision)].runs;
  }
  if (stages.Has(Effect::kCollision)) {
    StageTimer timer(stats[static_cast<int>(Effect::kCollision)]);
    FindContacts(tool, continuous, frame, scratch);
  }
  if (!stages.Has(Effect::kContactSet)) {
    scratch.pair_caches.FreeUnused();  // every one: none was used
    return;
  }
  StageTimer timer(stats[static_cast<int>(Effect::kContactSet)]);
  const PosedObject device = objects_.Posed(tool.id, tool.X_WD);
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
    const SceneObjects::Object& o = objects_[pair.object];
    PairCache& cache = scratch.pair_caches.For(pair.object);
    if (o.kind == ObjectKind::kTool) {
      ComputeToolContact(tool, tools_[index_[pair.object]], at_device, pair.contact, cache);
      continue;
    }
    const PosedObject other = objects_.Posed(pair.object, o.X_WO);
    // A pair found at an earlier sub-step is reported at that sub-step's
    // pose, along the motion: the tool passed through and no longer
    // touches at the end.
    const bool at_end = pair.substep == frame.substeps;
    const PosedObject at =
        at_end ? device
               : objects_.Posed(
                     tool.id, InterpolatePose(tool.X_WD_previous, tool.X_WD,
                                              static_cast<double>(pair.substep) / frame.substeps));
    absl::Status status =
        ComputeContact(at, other, at_end ? at_device : along_motion, pair.contact, &cache);
    if (continuous && status.ok() && !pair.contact.colliding) {
      status = ComputeContact(device, other, along_step, pair.contact, &cache);
    }
    if (!status.ok()) {  // as the collision stage left it
      ClearContactSet(pair.contact);
      pair.contact.colliding = true;
    }
  }
  scratch.pair_caches.FreeUnused();
}

int ToolStage::PairCachesHeld() const {
  int held = 0;
  for (const ToolScratch& scratch : scratch_) held += scratch.pair_caches.held();
  return held;
}

void ToolStage::ComputeToolContact(const Tool& tool, const Tool& other, const ContactQuery& query,
                                   ContactSet& contact, PairCache& cache) const {
  // Both devices went in from their proxies, which the last step left
  // apart: reversing the one's way in relative to the other's ends where
  // the proxies stood.
  const Vector3d from_proxies = (tool.X_WD.translation() - tool.X_WP.translation()) -
                                (other.X_WD.translation() - other.X_WP.translation());
  const Vector3d motion = (tool.X_WD.translation() - tool.X_WD_previous.translation()) -
                          (other.X_WD.translation() - other.X_WD_previous.translation());
  ContactQuery relative = query;
  relative.direction_W = from_proxies.squaredNorm() > 0 ? from_proxies : motion;
  relative.depth_hint_m = from_proxies.norm();
  const absl::Status status =
      ComputeContact(objects_.Posed(tool.id, tool.X_WD), objects_.Posed(other.id, other.X_WD),
                     relative, contact, &cache);
  if (!status.ok()) {  // as the collision stage left it
    ClearContactSet(contact);
    contact.colliding = true;
  }
}

void ToolStage::StepProxy(int index, std::span<const int> island, EffectSet stages,
                          ToolFrame& frame, ToolScratch& scratch) const {
  const Tool& tool = tools_[index];
  scratch.touched_tool = -1;
  const Vector3d motion = tool.X_WD.translation() - tool.X_WD_previous.translation();
  StageStatsTable& stats = scratch.proxy_stats;
  frame.X_WP = tool.X_WD;
  frame.touched_tool = -1;
  frame.force_W.setZero();
  frame.torque_W.setZero();
  frame.force_clamped = false;
  if (!stages.Has(Effect::kLocalModel)) {
    frame.local_model.planes.clear();
    frame.local_model.validity_radius_m = 0;
    frame.local_model.revision = 0;
  }
  // Friction runs inside the proxy stage: its runs are counted here, its
  // time is the proxy's.
  if (stages.Has(Effect::kFriction)) ++stats[static_cast<int>(Effect::kFriction)].runs;
  if (!stages.Has(Effect::kReversingVector)) return;
  ProxyState proxy;
  {
    StageTimer timer(stats[static_cast<int>(Effect::kReversingVector)]);
    const ProxyOptions options{.relative_tolerance = options_.relative_tolerance,
                               .friction = stages.Has(Effect::kFriction)};
    FindProxyObstacles(index, island, scratch);
    absl::StatusOr<ProxyState> moved = MoveProxy(objects_.Posed(tool.id, tool.X_WD), tool.X_WP,
                                                 tool.X_WD, scratch.proxy_obstacles, options);
    proxy = moved.ok() ? *moved : ProxyState{tool.X_WP};
    if (proxy.touching) proxy.obstacle = scratch.proxy_obstacle_ids[proxy.obstacle];
    frame.X_WP = proxy.X_WP;
    if (proxy.touching && objects_[proxy.obstacle].kind == ObjectKind::kTool) {
      frame.touched_tool = proxy.obstacle;
    }
  }
  if (stages.Has(Effect::kLocalModel)) {
    StageTimer timer(stats[static_cast<int>(Effect::kLocalModel)]);
    const double radius_m =
        scratch.model_radius_m > 0 ? scratch.model_radius_m : options_.local_model_radius_m;
    const LocalModelOptions model_options{.radius_m = radius_m,
                                          .force_clamp_n = options_.force_clamp_n,
                                          .friction = stages.Has(Effect::kFriction)};
    // A proxy that did not turn in its last move is searched for shifts
    // alone: fewer pairs, and the first turn searches again.
    const ProxyMoves moves =
        proxy.X_WP.linear() == tool.X_WP.linear() ? ProxyMoves::kShiftsOnly : ProxyMoves::kAny;
    const double margin =
        proxy.touching && moves == ProxyMoves::kShiftsOnly ? 0.0 : kPairMarginFraction * radius_m;
    auto gather = [&](double reach_m) {
      // Gathered for a pose ahead of the proxy along its last move, so
      // that the pairs serve it over nearly twice the way a search about
      // the proxy's own pose would, in the direction it goes.
      Isometry3d X_ahead = proxy.X_WP;
      const Vector3d move = proxy.X_WP.translation() - tool.X_WP.translation();
      const double move_m = move.norm();
      if (move_m > 0 && margin > 0) {
        X_ahead.translation() += (kAheadFraction * margin / move_m) * move;
      }
      GatherLocalModelPairs(objects_.Posed(tool.id, X_ahead), X_ahead, objects_.obstacles(),
                            objects_.obstacle_ids(), model_options, margin, reach_m, moves,
                            scratch.model_pairs);
      scratch.steps_since_search = 0;
      scratch.searched_radius_m = scratch.model_radius_m;
    };
    // The faces near the tool, shared by its models until the proxy moves
    // on (model_surface.h), gathered anew for a device that takes the tool
    // or asks for a fresh model (it is past the surface, or lost its faces).
    const std::shared_ptr<const ModelSurface>& surface = scratch.surfaces.Update(
        objects_.Posed(tool.id, proxy.X_WP), proxy.X_WP.translation(), radius_m,
        objects_.obstacles(), tool.seated || scratch.model_wanted);
    if (scratch.surface_only && surface) {
      // The device reads the surface alone: a model is the proxy's state
      // beside it, with no planes and no face search.
      if (tool.seated || scratch.model_wanted || scratch.surfaces.changed() ||
          SurfaceModelStale(scratch.model, proxy, model_options, ++scratch.steps_since_model,
                            options_.step_s)) {
        SurfaceOnlyModel(proxy, tool.X_WD.translation(), model_options, surface, scratch.model);
        scratch.steps_since_model = 0;
      }
    } else {
      const HapticObject& t = objects_[tool.id].object;
      // A device that takes the tool gets a model of its first pose: the
      // last one may be older than its stream.
      ModelUpdate update =
          tool.seated ? ModelUpdate::kBuild : ModelUpdateFor(proxy, model_options, scratch);
      // A new surface goes out with a new model, its planes the last ones
      // (they do not depend on the surface).
      scratch.built_model.surface = surface;
      if (update == ModelUpdate::kAnchor &&
          !AnchorLocalModel(scratch.built_model, proxy, tool.X_WD.translation(),
                            PlaneTouchTolerance(t), scratch.model)) {
        update = ModelUpdate::kBuild;
      }
      if (update == ModelUpdate::kBuild) {
        if (!PairsServe(proxy.X_WP, scratch))
          gather(SearchReach(scratch.built_model, model_options, margin));
        if (!ModelFromPairs(t, proxy, tool.X_WD.translation(), scratch.model_pairs, model_options,
                            scratch.built_model)) {
          // The model's farthest plane lies beyond a short search's pairs.
          gather(model_options.radius_m);
          (void)ModelFromPairs(t, proxy, tool.X_WD.translation(), scratch.model_pairs,
                               model_options,
                               scratch.built_model);  // the whole radius
        }
        MarkSeparatingPlanes(objects_.Posed(tool.id, proxy.X_WP), objects_.obstacles(),
                             objects_.obstacle_ids(), scratch.separation, scratch.built_model);
        scratch.built_model.revision = scratch.model.revision + 1;
        scratch.model = scratch.built_model;
      } else if (update == ModelUpdate::kAnchor) {
        ++scratch.model.revision;
      } else if (scratch.surfaces.changed()) {
        scratch.model.surface = surface;
        ++scratch.model.revision;
      }
      if (update != ModelUpdate::kKeep) scratch.steps_since_model = 0;
    }
    scratch.model_wanted = false;
    frame.local_model = scratch.model;
  }
  if (stages.Has(Effect::kForce) && proxy.touching) {
    StageTimer timer(stats[static_cast<int>(Effect::kForce)]);
    const SceneObjects::Object& touched = objects_[proxy.obstacle];
    const bool a_tool = touched.kind == ObjectKind::kTool;
    const Material& face = touched.object.face_material(proxy.face);
    const ToolForce force = SpringDamperForce(
        a_tool ? TouchingMaterial(objects_[tool.id].object.face_material(proxy.tool_face), face)
               : face,
        ToolContact{.p_WD = tool.X_WD.translation(),
                    .p_WP = proxy.X_WP.translation(),
                    .v_WD = motion / options_.step_s,
                    .normal_W = proxy.normal_W,
                    .p_WC = proxy.p_WC},
        options_.force_clamp_n);
    frame.force_W = force.force_W;
    frame.torque_W = force.torque_W;
    frame.force_clamped = force.clamped;
    if (a_tool) {
      scratch.touched_tool = proxy.obstacle;
      scratch.force_from_tool = force;
      scratch.p_WC = proxy.p_WC;
    }
  }
}

}  // namespace hs

#pragma once
// The tools of a scene and their step. A tool is posed by its device; each
// step finds what it touches (collision, sub-steps, contact sets: the
// contacts half) and moves its proxy and renders its force (the proxy
// half). Tools meet each other: a tool's contacts include the other tools
// at their device poses, and its proxy keeps out of the other tools'
// proxies. The tools whose proxies may meet this step form an island
// (tool_islands.h) whose proxies move one after the other, in tool order;
// the contacts halves and the islands read the state the last step left
// and write apart, so they run on the scene's worker threads at once, with
// results bit-identical whatever the number of threads. A tool whose
// proxy touches another tool pushes it back: the second device feels the
// first one's force turned round (action and reaction).

#include <span>
#include <utility>
#include <vector>

#include "common/core/scratch.h"
#include "common/sim/local_model_builder.h"
#include "common/sim/model_surface.h"
#include "common/sim/pair_caches.h"
#include "common/sim/scene_objects.h"
#include "common/sim/scene_options.h"
#include "common/sim/separating_planes.h"
#include "common/sim/step_frame.h"
#include "common/sim/tool_force.h"
#include "common/sim/tool_islands.h"
#include "common/sim/worker_pool.h"

namespace hs {

class ToolStage {
 public:
  /// `objects` outlives the stage; the stage poses its tools in the broad
  /// phase.
  ToolStage(const SceneOptions& options, SceneObjects& objects)
      : options_(options), objects_(objects) {}

  /// Makes object `id` (a tool of `objects`) a tool at X_WO, device and
  /// proxy alike.
  void Add(ObjectId id, const Isometry3d& X_WO);
  /// The device pose of tool `id` for the next step; `id` must be a tool.
  void SetDevicePose(ObjectId id, const Isometry3d& X_WD);
  /// The first pose of a device that has just taken tool `id`: nothing is
  /// swept from the last device's pose, and the proxy moves to it from the
  /// tool's home pose (where Add put it).
  void SeatDevice(ObjectId id, const Isometry3d& X_WD);
  /// No device moved since the last step, no proxy moved in it, no tool
  /// wants a fresh local model and no object was added: the step holds the
  /// last frame (docs/simulation.md, Still devices).
  bool NothingToStep() const;
  /// Tool `id`'s next step builds a fresh local model (its device went past
  /// the last one's validity sphere); `id` must be a tool.
  void RequestLocalModel(ObjectId id);
  /// Tool `id`'s local models take validity radius `radius_m` (metres,
  /// > 0, already within the scene's bounds) from its next step; `id`
  /// must be a tool.
  void SetLocalModelRadius(ObjectId id, double radius_m);
  /// Tool `id`'s models carry no planes beside a surface (Scene::SetSurfaceOnly).
  void SetSurfaceOnly(ObjectId id, bool surface_only);

  /// Steps every tool through `stages` on `workers`: `frames` takes one
  /// entry per tool (in the order added), `stats` each stage's runs and
  /// time. Stages that fail on a pair leave that pair out.
  void Step(EffectSet stages, WorkerPool& workers, std::vector<ToolFrame>& frames,
            StageStatsTable& stats);

  /// Tool `id`'s proxy pose after the last step and its move over that
  /// step, world frame, metres: where free bodies meet the tool.
  struct ProxyMotion {
    Isometry3d X_WP;
    Vector3d motion_W;
  };
  ProxyMotion ProxyMotionOf(ObjectId id) const;

  /// The pair caches the tools hold (PairCaches): none unless the contact
  /// set stage ran in the last step.
  int PairCachesHeld() const;

 private:
  struct Tool {
    ObjectId id;
    Isometry3d X_WD_previous;  // device pose of the last step
    Isometry3d X_WD;           // device pose for the next step
    Isometry3d X_WP;           // proxy pose
    Isometry3d X_WP_previous;  // proxy pose of the last step
    Isometry3d X_WO_home;      // where Add put it
    bool moved = true;
    // Its proxy moved in the last step: it may not rest yet (a slide the
    // step's slides did not finish, friction creep), so it steps on.
    bool sliding = false;
    bool seated = false;  // SeatDevice since the last step
    // Its proxy's island of the last step held no other tool.
    bool alone = false;
    // This step holds the tool's last frame (Holds).
    bool held = false;
  };
  // What one tool's step writes besides its frame, so that tools, and the
  // two halves of a tool's step, can be stepped at once: each half writes
  // its own members only.
  struct ToolScratch {
    // The contacts half. FindCandidates: indices into targets(), ascending.
    std::vector<int> candidates;
    // The proxy half. FindProxyObstacles: a subset of obstacles(), in
    // order, then the tools of the island, and their ids.
    std::vector<PosedObject> proxy_obstacles;
    std::vector<ObjectId> proxy_obstacle_ids;
    // The proxy half: the proxy pose as far as this step has moved it,
    // which the tools after it in its island keep out of.
    Isometry3d X_WP_now = Isometry3d::Identity();
    // The proxy half, for the reaction: the tool its proxy touches (-1:
    // none, or the force stage did not run), the force it feels from it
    // and the touching point, world frame.
    ObjectId touched_tool = -1;
    ToolForce force_from_tool;
    Vector3d p_WC = Vector3d::Zero();
    // The contacts half: the contact sets of the last step's pairs, their
    // storage kept for this step's (a step allocates nothing once the
    // vectors are large enough).
    std::vector<ContactSet> spare_contacts;
    // The contacts half, with the contact set stage: the caches of the
    // pairs whose contact sets it reconstructs.
    PairCaches pair_caches;
    // Each half's stages' runs and times of this step, added to the
    // scene's after it.
    StageStatsTable contact_stats{};
    StageStatsTable proxy_stats{};
    // Each half's query buffers: the same ones whichever worker runs it,
    // so that they stop growing once each half has met its largest contact.
    ScratchSpace contacts_space;
    ScratchSpace proxy_space;
    // The proxy half, with the local model stage: the feature pairs of the
    // last face search, which serve until the proxy moves past their
    // margin (PairsServe), the steps since, whether a device asked for a
    // fresh model, the model last made from the pairs at a step's proxy,
    // and the one the frames carry: that one, or it anchored at a touching
    // proxy that has slid since (local_model_anchor.h).
    LocalModelPairs model_pairs;
    int steps_since_search = 0;
    int steps_since_model = 0;
    bool model_wanted = false;
    // The validity radius the tool's device asked for (0: the scene's),
    // and the one the pairs were searched with.
    double model_radius_m = 0;
    double searched_radius_m = 0;
    // The tool's device reads the surface alone: a model with a surface
    // carries no planes.
    bool surface_only = false;
    LocalModel built_model;
    // Which planes of the last model built separate (separating_planes.h).
    SeparationMemo separation;
    // The surface the tool's models share (model_surface.h).
    SurfaceKeeper surfaces;
    LocalModel model;
  };
  // A piece of a step for one worker: the contacts half of tool `index`
  // (into tools_), or the proxy halves of island `index`.
  struct StepJob {
    int index;
    bool contacts;
  };
  enum class Candidates {
    kAtDevicePose,  // the broad phase's pairs at the device pose
    kSwept,         // boxes overlapping the tool's box swept along the step
    kEvery,         // every target (options_.broad_phase off)
  };

  // Groups the tools' reach boxes into islands_, and marks each tool that
  // this step holds (Tool::held).
  void GroupIslands(EffectSet stages);
  // A tool whose device sent no changed pose, whose proxy did not move in
  // the last step, that wants no fresh model,
  // whose island held no other tool in the last step nor in this one, in a
  // step of the same stages and objects without free bodies: its step
  // would bring no new information (docs/simulation.md, Still devices),
  // and it keeps its last frame.
  bool Holds(int index, EffectSet stages, bool alone) const;
  // No object was added since the last step (objects are only added).
  bool SameObstacles() const;
  void RunJob(StepJob job, EffectSet stages, std::vector<ToolFrame>& frames);
  // The proxy halves of an island's tools (indices into tools_), in order.
  void StepIsland(std::span<const int> island, EffectSet stages, std::vector<ToolFrame>& frames);
  // Adds to the force of each tool another tool's proxy touched that
  // tool's force turned round.
  void AddToolReactions(std::vector<ToolFrame>& frames);
  // The contacts half: frame.contacts and frame.substeps (collision,
  // contact sets).
  void StepContacts(const Tool& tool, EffectSet stages, ToolFrame& frame,
                    ToolScratch& scratch) const;
  // The proxy half: frame.X_WP and the force (reversing vector, force,
  // friction).
  // `island` holds the tool (indices into tools_).
  void StepProxy(int index, std::span<const int> island, EffectSet stages, ToolFrame& frame,
                 ToolScratch& scratch) const;
  // What the tool's last model needs to serve its proxy at `proxy`, for a
  // model of `options` (docs/simulation.md, Local models only when
  // needed); counts the step.
  enum class ModelUpdate {
    kKeep,    // it serves as it is
    kAnchor,  // the last one built, anchored at the proxy
    kBuild,   // a new one
  };
  ModelUpdate ModelUpdateFor(const ProxyState& proxy, const LocalModelOptions& options,
                             ToolScratch& scratch) const;
  // Whether the pairs of the last face search still serve the tool's
  // model with its proxy at X_WP (docs/simulation.md, Local models only
  // when needed); counts the step.
  bool PairsServe(const Isometry3d& X_WP, ToolScratch& scratch) const;
  // Fills scratch.candidates with the targets the tool may touch this step.
  void FindCandidates(const Tool& tool, Candidates which, ToolScratch& scratch) const;
  // Fills scratch.proxy_obstacles with the fixed objects and the proxies of
  // the other tools of `island` that tool `index`'s proxy may touch.
  void FindProxyObstacles(int index, std::span<const int> island, ToolScratch& scratch) const;
  // Whether tool `index`'s proxy, turned to its device's orientation,
  // already penetrates tool `other`'s proxy (a device seated where
  // another tool stands): they do not block each other until apart.
  bool ProxiesPenetrate(int index, int other) const;
  // The contact of `tool` with `other`, both at their device poses, along
  // the way in of the one relative to the other, through the pair's cache.
  void ComputeToolContact(const Tool& tool, const Tool& other, const ContactQuery& query,
                          ContactSet& contact, PairCache& cache) const;
  // Adds a pair for each other tool the tool touches at the device poses.
  void FindToolContacts(const Tool& tool, ToolFrame& frame, ToolScratch& scratch) const;
  // The collision stage of one tool, sub-stepped when its step is long.
  void FindContacts(const Tool& tool, bool continuous, ToolFrame& frame,
                    ToolScratch& scratch) const;

  const SceneOptions& options_;
  SceneObjects& objects_;
  std::vector<Tool> tools_;
  // Per object id: its index in tools_, -1 for other kinds (grown on Add).
  std::vector<int> index_;
  // Per tool, in tools_' order.
  std::vector<ToolScratch> scratch_;
  // The jobs of this step that have a stage to run.
  std::vector<StepJob> jobs_;
  // Per tool: the box of every pose its proxy may take this step; and the
  // islands they make.
  std::vector<AlignedBox3d> reach_boxes_;
  ToolIslands islands_;
  // The stages of the last step (none before the first), and how many
  // objects the proxies kept out of then.
  EffectSet last_stages_;
  size_t last_obstacle_count_ = 0;
  // The broad phase's pairs at the device poses, once per step that runs
  // the collision stage without continuous collision.
  std::vector<std::pair<ObjectId, ObjectId>> broad_pairs_;
};

}  // namespace hs

#pragma once
// The tools of a scene and their step. A tool is posed by its device; each
// step finds what it touches (collision, sub-steps, contact sets: the
// contacts half) and moves its proxy and renders its force (the proxy
// half). The halves of every tool read the state the last step left and
// write apart, so they run on the scene's worker threads at once, with
// results bit-identical whatever the number of threads.

#include <utility>
#include <vector>

#include "common/core/scratch.h"
#include "common/sim/scene_objects.h"
#include "common/sim/scene_options.h"
#include "common/sim/step_frame.h"
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
  /// Some device moved since the last step.
  bool AnyMoved() const;

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

 private:
  struct Tool {
    ObjectId id;
    Isometry3d X_WD_previous;  // device pose of the last step
    Isometry3d X_WD;           // device pose for the next step
    Isometry3d X_WP;           // proxy pose
    Isometry3d X_WP_previous;  // proxy pose of the last step
    Isometry3d X_WO_home;      // where Add put it
    bool moved = true;
    bool seated = false;  // SeatDevice since the last step
  };
  // What one tool's step writes besides its frame, so that tools, and the
  // two halves of a tool's step, can be stepped at once: each half writes
  // its own members only.
  struct ToolScratch {
    // The contacts half. FindCandidates: indices into targets(), ascending.
    std::vector<int> candidates;
    // The proxy half. FindProxyObstacles: a subset of obstacles(), in
    // order, and their ids.
    std::vector<PosedObject> proxy_obstacles;
    std::vector<ObjectId> proxy_obstacle_ids;
    // The contacts half: the contact sets of the last step's pairs, their
    // storage kept for this step's (a step allocates nothing once the
    // vectors are large enough).
    std::vector<ContactSet> spare_contacts;
    // Each half's stages' runs and times of this step, added to the
    // scene's after it.
    StageStatsTable contact_stats{};
    StageStatsTable proxy_stats{};
    // Each half's query buffers: the same ones whichever worker runs it,
    // so that they stop growing once each half has met its largest contact.
    ScratchSpace contacts_space;
    ScratchSpace proxy_space;
  };
  // One half of tool `tool`'s step (an index into tools_).
  struct ToolHalf {
    int tool;
    bool contacts;  // else the proxy half
  };
  enum class Candidates {
    kAtDevicePose,  // the broad phase's pairs at the device pose
    kSwept,         // boxes overlapping the tool's box swept along the step
    kEvery,         // every target (options_.broad_phase off)
  };

  void StepHalf(ToolHalf half, EffectSet stages, std::vector<ToolFrame>& frames);
  // The contacts half: frame.contacts and frame.substeps (collision,
  // contact sets).
  void StepContacts(const Tool& tool, EffectSet stages, ToolFrame& frame,
                    ToolScratch& scratch) const;
  // The proxy half: frame.X_WP and the force (reversing vector, force,
  // friction).
  void StepProxy(const Tool& tool, EffectSet stages, ToolFrame& frame, ToolScratch& scratch) const;
  // Fills scratch.candidates with the targets the tool may touch this step.
  void FindCandidates(const Tool& tool, Candidates which, ToolScratch& scratch) const;
  // Fills scratch.proxy_obstacles with the fixed objects the proxy may touch.
  void FindProxyObstacles(const Tool& tool, ToolScratch& scratch) const;
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
  // The halves of this step that have a stage to run.
  std::vector<ToolHalf> halves_;
  // The broad phase's pairs at the device poses, once per step that runs
  // the collision stage without continuous collision.
  std::vector<std::pair<ObjectId, ObjectId>> broad_pairs_;
};

}  // namespace hs

#pragma once
// A scene: fixed objects, free bodies (moved by the simulation) and tools
// (posed from outside each step), stepped at a fixed rate. Each step runs
// only the stages (effects) the scene enables and its consumers need, and
// counts their runs and time.

#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "common/collision/broad_phase.h"
#include "common/collision/collision_model.h"
#include "common/sim/free_body.h"
#include "common/sim/proxy.h"
#include "common/sim/step_frame.h"
#include "common/sim/worker_pool.h"

namespace hs {

enum class ObjectKind {
  kFixed,  ///< Never moves.
  kTool,   ///< Posed by a device before each step.
  kFree,   ///< Moved by the simulation (free-body motion), pushed by the others.
};

/// The inertia and start velocities of a free body (ignored for other kinds).
struct BodyOptions {
  /// Mass, kilograms; 0 takes density x the mesh's volume.
  double mass_kg = 0;
  /// Density, kg/m^3, used when mass_kg is 0.
  double density_kg_per_m3 = 1000;
  /// Start velocity of the centre of mass and angular velocity, world frame,
  /// m/s and rad/s.
  Vector3d v_W = Vector3d::Zero();
  Vector3d w_W = Vector3d::Zero();
};

struct SceneOptions {
  /// Simulated time per step, seconds. Finite and > 0.
  double step_s = 1e-3;
  /// The effects this scene allows.
  EffectSet enabled = EffectSet::All();
  ContactMethod method = ContactMethod::kSweep3d;
  BvType bv = BvType::kObbRss;
  /// Touching tolerance relative to a pair's size (ContactQuery); <= 1e-6.
  double relative_tolerance = 1e-9;
  /// The largest force rendered on a tool, newtons. Finite and > 0.
  double force_clamp_n = 10;
  /// Acceleration of free bodies by gravity, world frame, m/s^2. Finite.
  Vector3d gravity_W = Vector3d(0, 0, -9.81);
  /// How fast a free body's spin dies while it touches something, 1/s
  /// (w decays as exp(-rate t)); finite and >= 0. One impulse point per
  /// contact leaves a body rocking on a face without it; free flight is
  /// not damped.
  double contact_angular_damping_per_s = 20;
  /// Pick the pairs to test by their boxes: FCL's dynamic AABB tree
  /// (BroadPhase) at the step's end poses, or the boxes swept along the
  /// step when continuous collision or sub-stepping is on. False tests
  /// every pair (same results, slower: the oracle of the tests).
  bool broad_phase = true;
};

class Scene {
 public:
  /// INVALID_ARGUMENT when an option is out of range.
  static absl::StatusOr<std::unique_ptr<Scene>> Create(const SceneOptions& options);

  /// Adds `object` at X_WO (world frame, metres) and returns its id; `body`
  /// gives a free body's inertia and start velocities. INVALID_ARGUMENT when
  /// the pose is not finite or not rigid, or a free body's mass, density or
  /// velocities are not finite and positive (velocities: finite).
  absl::StatusOr<ObjectId> AddObject(HapticObject object, ObjectKind kind, const Isometry3d& X_WO,
                                     const BodyOptions& body = {});

  /// The device pose of tool `id` for the next step. NOT_FOUND for an
  /// unknown id, FAILED_PRECONDITION when it is not a tool,
  /// INVALID_ARGUMENT when the pose is not finite or not rigid; nothing
  /// changes on error.
  absl::Status SetDevicePose(ObjectId id, const Isometry3d& X_WD);

  /// Steps the tools on up to `threads` threads (the stepping one
  /// included): tools never meet each other, so each is stepped alone, its
  /// contacts apart from its proxy and force, and the results are
  /// bit-identical whatever the number. Stage times are
  /// then summed over the threads. Each new worker thread first runs
  /// `on_worker_start` when set. INVALID_ARGUMENT outside [1, 64].
  absl::Status SetThreads(int threads, const std::function<void()>& on_worker_start = {});

  /// What the scene's consumers need from now on (their union).
  void SetNeeded(EffectSet needed) { needed_ = needed; }

  /// Runs one step and returns its frame (valid until the next Step).
  /// Stages that fail on a pair (they do not, for validated input) leave
  /// that pair out of the frame.
  const StepFrame& Step();

  const StageStatsTable& stats() const { return stats_; }
  const SceneOptions& options() const { return options_; }

 private:
  struct Object {
    HapticObject object;
    CollisionModel model;
    ObjectKind kind;
    Isometry3d X_WO;
  };
  struct Tool {
    ObjectId id;
    Isometry3d X_WD_previous;  // device pose of the last step
    Isometry3d X_WD;           // device pose for the next step
    Isometry3d X_WP;           // proxy pose
    Isometry3d X_WP_previous;  // proxy pose of the last step
    bool moved = true;
    // Impulse the tool gave free bodies this step, world frame, N*s.
    Vector3d push_impulse_W = Vector3d::Zero();
  };
  // What one tool's step writes besides its frame, so that tools, and the
  // two halves of a tool's step, can be stepped at once: each half writes
  // its own members only.
  struct ToolScratch {
    // StepToolContacts. FindCandidates: indices into targets_, ascending.
    std::vector<int> candidates;
    // StepToolProxy. FindProxyObstacles: a subset of obstacles_, in order,
    // and their ids.
    std::vector<PosedObject> proxy_obstacles;
    std::vector<ObjectId> proxy_obstacle_ids;
    // Each half's stages' runs and times of this step, added to stats_
    // after it.
    StageStatsTable contact_stats{};
    StageStatsTable proxy_stats{};
  };
  struct Body {
    ObjectId id;
    MassProperties mass;
    FreeBodyState state;
    Isometry3d X_WO_start;  // pose at the start of the current step
  };
  // The other side of a free body's contact, as the response needs it.
  struct Counterpart {
    Isometry3d X_WO = Isometry3d::Identity();
    Vector3d motion_W = Vector3d::Zero();  // its displacement this step, metres
    Vector3d v_W = Vector3d::Zero();       // its velocity, m/s (tools)
    OtherBody body;                        // set when it is free
  };

  explicit Scene(const SceneOptions& options) : options_(options) {}
  PosedObject Posed(const Object& o, const Isometry3d& X) const { return {&o.object, &o.model, X}; }
  // The two halves of a tool's step. Both read the tool's state as the last
  // step left it (the proxy too) and write apart: the contacts half
  // frame.contacts and frame.substeps (collision, contact sets); the proxy
  // half frame.X_WP and the force (reversing vector, force, friction).
  void StepToolContacts(const Tool& tool, EffectSet stages, ToolFrame& frame,
                        ToolScratch& scratch) const;
  void StepToolProxy(const Tool& tool, EffectSet stages, ToolFrame& frame,
                     ToolScratch& scratch) const;
  // One half of tool `tool`'s step (an index into tools_).
  struct ToolHalf {
    int tool;
    bool contacts;  // else the proxy half
  };
  void StepHalf(ToolHalf half, EffectSet stages);
  void MoveFreeBody(Body& body, BodyFrame& frame);
  // Adds the reaction of the free bodies the tool pushed to its force.
  void AddPushReaction(const Tool& tool, ToolFrame& frame) const;
  Counterpart CounterpartOf(ObjectId id);
  enum class Candidates {
    kAtDevicePose,  // the broad phase's pairs at the device pose
    kSwept,         // boxes overlapping the tool's box swept along the step
    kEvery,         // every target (options_.broad_phase off)
  };
  // Fills scratch.candidates with the targets the tool may touch this step.
  void FindCandidates(const Tool& tool, Candidates which, ToolScratch& scratch) const;
  // Fills scratch.proxy_obstacles with the fixed objects the proxy may touch.
  void FindProxyObstacles(const Tool& tool, ToolScratch& scratch) const;
  // The collision stage of one tool, sub-stepped when its step is long.
  void FindToolContacts(const Tool& tool, bool continuous, ToolFrame& frame,
                        ToolScratch& scratch) const;
  // How far to move `self` (at X_WO) along the unit normal n to stop
  // penetrating `that`, from `contact` found along `motion_W`.
  double SeparationAlongNormal(const Object& self, const Isometry3d& X_WO, const Object& that,
                               const Isometry3d& X_WO_other, const ContactSet& contact,
                               const Vector3d& motion_W, const Vector3d& n) const;
  // Resolves one contact of `body` (moved from X_WO_from this sub-step)
  // with object `other`; returns whether they were in contact.
  bool ResolveContact(Body& body, const Isometry3d& X_WO_from, ObjectId other);

  SceneOptions options_;
  EffectSet needed_ = EffectSet::All();
  std::vector<std::unique_ptr<Object>> objects_;
  // Per object id: its index in tools_ or bodies_ (-1 when fixed).
  std::vector<int> slots_;
  std::vector<Tool> tools_;
  std::vector<Body> bodies_;
  // The fixed objects, posed, and their ids: built once as objects are
  // added, not every step. The proxy keeps out of these.
  std::vector<PosedObject> obstacles_;
  std::vector<ObjectId> obstacle_ids_;
  // The fixed objects and free bodies, posed (free bodies as of the start
  // of the step), and their ids: a tool's contacts are reported with these.
  std::vector<PosedObject> targets_;
  std::vector<ObjectId> target_ids_;
  // targets_' world boxes, grown by their models' margins.
  std::vector<AlignedBox3d> target_boxes_;
  // Per object id: its index in targets_ (-1 for tools).
  std::vector<int> target_index_;
  // The shortest bounding-box edge of any object, metres: no free body
  // moves farther in one sub-step.
  double smallest_edge_m_ = std::numeric_limits<double>::infinity();
  // Every object at its current pose (tools at the device pose), keyed by
  // id; its pairs are computed before the tools are stepped, once per step
  // that runs the collision stage without continuous collision.
  BroadPhase broad_phase_;
  std::vector<std::pair<BroadPhase::Key, BroadPhase::Key>> broad_pairs_;
  // Per tool, in tools_' order.
  std::vector<ToolScratch> scratch_;
  // The halves of this step's tool steps that have a stage to run.
  std::vector<ToolHalf> halves_;
  std::unique_ptr<WorkerPool> workers_ = std::make_unique<WorkerPool>(1);
  StageStatsTable stats_{};
  StepFrame frame_;
};

}  // namespace hs

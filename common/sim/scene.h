#pragma once
// A scene: fixed objects, free bodies (moved by the simulation) and tools
// (posed from outside each step), stepped at a fixed rate. Each step runs
// only the stages (effects) the scene enables and its consumers need, and
// counts their runs and time. Its parts: the posed-object index
// (scene_objects.h), the tool stage (tool_stage.h: contacts, proxy,
// force) and the free bodies (free_bodies.h).

#include <functional>
#include <memory>

#include "absl/status/statusor.h"
#include "common/sim/free_bodies.h"
#include "common/sim/local_model_request.h"
#include "common/sim/scene_objects.h"
#include "common/sim/scene_options.h"
#include "common/sim/step_frame.h"
#include "common/sim/tool_stage.h"
#include "common/sim/worker_pool.h"

namespace hs {

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
  /// Like SetDevicePose, for a device that has just taken tool `id`: its
  /// pose does not follow the last device's, so nothing is swept between
  /// them, and the proxy comes to it from the tool's home pose (where the
  /// scene placed the tool) instead of from where the last device left it,
  /// stopping at what lies between as a proxy does.
  absl::Status SeatDevice(ObjectId id, const Isometry3d& X_WD);
  /// Tool `id`'s next step builds a fresh local model (a device went past
  /// the last one's validity sphere). NOT_FOUND or FAILED_PRECONDITION, as
  /// SetDevicePose, when `id` is no tool.
  absl::Status RequestLocalModel(ObjectId id);
  /// Tool `id`'s local models from its next step have the validity radius
  /// its device asked for (ToolPose.validity_radius_m), metres, taken
  /// within [local_model_radius_m, local_model_radius_cap_m]; 0 returns to
  /// the scene's. INVALID_ARGUMENT when not finite or negative; NOT_FOUND
  /// or FAILED_PRECONDITION, as SetDevicePose, when `id` is no tool.
  absl::Status SetLocalModelRadius(ObjectId id, double radius_m);
  /// Whether tool `id`'s device reads its local model's surface alone
  /// (InteractRequest.Open.surface_only): from its next step, a model
  /// with a surface then carries no planes, and costs no plane search.
  /// NOT_FOUND or FAILED_PRECONDITION, as SetDevicePose, when `id` is no
  /// tool.
  absl::Status SetSurfaceOnly(ObjectId id, bool surface_only);

  /// Steps the tools on up to `threads` threads (the stepping one
  /// included): each tool's contacts apart from its proxy and force, the
  /// proxies of tools that may meet one after the other (tool_stage.h),
  /// and the results are bit-identical whatever the number. Stage times
  /// are then summed over the threads. A step whose tools took less than
  /// SceneOptions::parallel_work_share of the step period, summed over the
  /// threads, is followed by one on the stepping thread alone. Each new
  /// worker thread first runs `on_worker_start` when set.
  /// INVALID_ARGUMENT outside [1, 64].
  absl::Status SetThreads(int threads, const std::function<void()>& on_worker_start = {});

  /// What the scene's consumers need from now on (their union).
  void SetNeeded(EffectSet needed) { needed_ = needed; }

  /// Runs one step and returns its frame (valid until the next Step).
  /// Stages that fail on a pair (they do not, for validated input) leave
  /// that pair out of the frame.
  const StepFrame& Step();

  const StageStatsTable& stats() const { return stats_; }
  /// The pair caches the scene keeps between steps for the contact set
  /// stage (common/sim/pair_caches.h): none when it did not run last step.
  int pair_caches_held() const { return tools_.PairCachesHeld(); }
  /// The objects as the scene holds them (HDS, kind, pose), by ObjectId.
  int num_objects() const { return objects_.size(); }
  const SceneObjects::Object& object(ObjectId id) const { return objects_[id]; }
  const SceneOptions& options() const { return options_; }

 private:
  // NOT_FOUND or FAILED_PRECONDITION when `id` is no tool.
  absl::Status CheckTool(ObjectId id) const;
  // SetDevicePose's errors.
  absl::Status CheckDevicePose(ObjectId id, const Isometry3d& X_WD) const;
  explicit Scene(const SceneOptions& options) : options_(options) {}

  SceneOptions options_;
  EffectSet needed_ = EffectSet::Default();
  EffectSet last_stages_;  // the stages the last step that ran any ran
  SceneObjects objects_;
  ToolStage tools_{options_, objects_};
  FreeBodies bodies_{options_, objects_};
  std::unique_ptr<WorkerPool> workers_ = std::make_unique<WorkerPool>(1);
  StageStatsTable stats_{};
  StepFrame frame_;
};

/// SeatDevice for a device's first pose on the tool, else SetDevicePose.
inline absl::Status ApplyDevicePose(Scene& scene, ObjectId id, const Isometry3d& X_WD, bool seat) {
  return seat ? scene.SeatDevice(id, X_WD) : scene.SetDevicePose(id, X_WD);
}

/// Asks the scene for what `model` says of tool `id`'s local model
/// (RequestLocalModel when stale, SetLocalModelRadius, SetSurfaceOnly):
/// their errors, the first one met.
absl::Status ApplyLocalModelRequest(Scene& scene, ObjectId id, const LocalModelRequest& model);

}  // namespace hs

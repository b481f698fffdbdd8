#pragma once
// A scene: fixed objects and tools (posed from outside each step), stepped
// at a fixed rate. Each step runs only the stages (effects) the scene
// enables and its consumers need, and counts their runs and time.

#include <memory>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "common/collision/collision_model.h"
#include "common/sim/proxy.h"
#include "common/sim/step_frame.h"

namespace hs {

enum class ObjectKind {
  kFixed,  ///< Never moves.
  kTool,   ///< Posed by a device before each step.
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
};

class Scene {
 public:
  /// INVALID_ARGUMENT when an option is out of range.
  static absl::StatusOr<std::unique_ptr<Scene>> Create(const SceneOptions& options);

  /// Adds `object` at X_WO (world frame, metres) and returns its id.
  /// INVALID_ARGUMENT when the pose is not finite or not rigid.
  absl::StatusOr<ObjectId> AddObject(HapticObject object, ObjectKind kind, const Isometry3d& X_WO);

  /// The device pose of tool `id` for the next step. NOT_FOUND for an
  /// unknown id, FAILED_PRECONDITION when it is not a tool,
  /// INVALID_ARGUMENT when the pose is not finite or not rigid; nothing
  /// changes on error.
  absl::Status SetDevicePose(ObjectId id, const Isometry3d& X_WD);

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
    bool moved = true;
  };

  explicit Scene(const SceneOptions& options) : options_(options) {}
  PosedObject Posed(const Object& o, const Isometry3d& X) const { return {&o.object, &o.model, X}; }
  void StepTool(Tool& tool, EffectSet stages, ToolFrame& frame);

  SceneOptions options_;
  EffectSet needed_ = EffectSet::All();
  std::vector<std::unique_ptr<Object>> objects_;
  std::vector<Tool> tools_;
  // The fixed objects, posed, and their ids: built once as objects are
  // added, not every step.
  std::vector<PosedObject> obstacles_;
  std::vector<ObjectId> obstacle_ids_;
  StageStatsTable stats_{};
  StepFrame frame_;
};

}  // namespace hs

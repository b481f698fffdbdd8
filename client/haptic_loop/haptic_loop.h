#pragma once
// A remote device's own 1 kHz haptic loop: renders contact from the latest
// local contact model (common/sim/local_model.h) between the frames that
// bring it, so that the force follows the hand at the device's rate
// whatever the round trip. No gRPC and no simulation in it: a device
// vendor's loop links this library (and Eigen) alone.
//
// Each tick: the proxy (a god object, as the server's common/sim/proxy.h)
// moves from where it was toward the device, stopping at the first plane
// it meets and sliding along it toward the device (Coulomb friction when
// the model says so), at most three slides; the force is the touched
// plane's spring from the device to the proxy and its damper along the
// normal, clamped to the scene's clamp, with its torque. A new model
// restarts the proxy where the server's was (the server's god object
// knows the whole mesh); the step between what the old and the new model
// render at that tick is spread over the next ticks, so that no tick
// changes the force by more than `max_switch_step_n` on that account. The proxy never leaves the
// model's validity sphere: past it the model says nothing, so the loop does not extrapolate. A
// non-finite pose or model is rejected: the loop holds its last force (or model) and counts the
// rejection.

#include <cstdint>

#include "common/core/types.h"
#include "common/sim/local_model.h"

namespace hs {

struct HapticLoopOptions {
  /// The loop's period, seconds (the device velocity is taken over it).
  double tick_s = 1e-3;
  /// The most a new model may change the force in one tick, newtons.
  double max_switch_step_n = 0.25;
  /// Stops and slides per tick, as the server's proxy.
  int max_slides = 3;
};

struct HapticOutput {
  /// On the device, world frame, N and N*m (about the device origin).
  Vector3d force_W = Vector3d::Zero();
  Vector3d torque_W = Vector3d::Zero();
  /// The proxy's origin, world frame, metres.
  Vector3d p_WP = Vector3d::Zero();
  bool touching = false;
  bool clamped = false;
  /// The device was farther from the model's proxy than its validity radius.
  bool beyond_validity = false;
};

class HapticLoop {
 public:
  explicit HapticLoop(const HapticLoopOptions& options = {}) : options_(options) {}

  /// Renders from `model` from the next tick on. A model with a number that
  /// is not finite, a normal that is not unit, or a radius or clamp that is
  /// not > 0 is rejected (false; the last model stays).
  bool SetModel(const LocalModel& model);

  /// One tick with the device at X_WD (world frame, metres). A non-finite
  /// pose returns the last output unchanged (counted).
  HapticOutput Tick(const Isometry3d& X_WD);

  bool has_model() const { return has_model_ || has_pending_model_; }
  /// Models and poses rejected so far.
  int64_t rejected_models() const { return rejected_models_; }
  int64_t rejected_poses() const { return rejected_poses_; }
  /// Ticks whose device lay past the model's validity radius.
  int64_t beyond_validity_ticks() const { return beyond_validity_ticks_; }

 private:
  // Moves proxy_ toward `goal` against the model's planes; returns the
  // plane last touched, -1 for none.
  int MoveProxy(const Vector3d& device, const Vector3d& goal);
  // One tick's proxy move and force against model_.
  HapticOutput Step(const Vector3d& device, const Vector3d& v_WD);
  // The force of touching plane `plane` with the device at `device`
  // moving at `v_WD`.
  HapticOutput Render(int plane, const Vector3d& device, const Vector3d& v_WD) const;

  HapticLoopOptions options_;
  LocalModel model_;
  bool has_model_ = false;
  // The model SetModel took, rendered from the next tick.
  LocalModel pending_model_;
  bool has_pending_model_ = false;
  Vector3d proxy_ = Vector3d::Zero();
  Vector3d last_device_ = Vector3d::Zero();
  bool has_last_device_ = false;
  // What a model switch left to spread over the next ticks, newtons.
  Vector3d switch_offset_ = Vector3d::Zero();
  HapticOutput last_;
  int64_t rejected_models_ = 0;
  int64_t rejected_poses_ = 0;
  int64_t beyond_validity_ticks_ = 0;
};

}  // namespace hs

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
// normal, clamped to the scene's clamp, with its torque.
//
// A new model arrives a round trip after the device pose it was taken at
// (`LocalModel::p_WD`). The loop finds the tick it rendered that pose at
// and moves its proxy by how far the server's proxy then differed from its
// own (the server's god object knows the whole mesh), from the server's
// proxy toward that place: the proxy stays where the hand has taken it
// since, corrected, rather than jumping back a round trip (which would
// drag the hand back and, when it turns, push it on). A model whose pose
// the loop no longer holds restarts the proxy where the server's was. The
// step between what the old and the new model render at that tick is
// spread over the next ticks, so that no tick changes the force by more
// than `max_switch_step_n` on that account; the sum stays within the clamp.
// Past the model's validity sphere the model says nothing, so the loop
// does not extrapolate: the proxy is rendered at the sphere's edge, and
// only the touched plane's push along its normal is felt (no friction and
// no drag back toward the sphere, which would be forces no surface makes).
// A model with a surface (local_model.h, ModelSurface: the faces near the
// tool and the tool's convex hull) is rendered from the surface instead:
// the proxy sweeps the tool against the faces themselves (surface_sweep.h),
// as the server's proxy sweeps it against the objects, so what the loop
// renders does not depend on where or when its model was taken. A new
// model then leaves the proxy where it is (the objects are the same), as
// long as it is within the surface's sphere and in no face; else the proxy
// restarts at the server's and that step is spread as a switch's. The
// validity sphere is then the surface's. A model that names a surface the
// loop has not got renders from its planes.
// A non-finite pose or model is rejected: the loop holds its last force
// (or model) and counts the rejection. Nothing is allocated once the
// loop has held its largest model.
//
// Time-domain passivity (Hannaford and Ryu 2002): the loop observes the
// work its force does on the hand (each tick's force times the device's
// move over the next tick). A model a round trip old may switch planes
// under a moving hand and so hand it energy no surface would. The contact
// may hand back what the touched plane's spring holds (and
// `passivity_reserve_j`), no more: the energy friction and the dampers
// took from the hand is gone (a long slide's friction never pays for a
// later kick), and in free space nothing is held. When this tick's force,
// on the hand's present velocity, would hand back more, the loop adds a
// damper against the velocity that takes the excess back, at most
// `max_passivity_damping_ns_per_m` (a damper a device and a hand hold
// stably at 1 kHz), its force changing by at most `max_switch_step_n` a
// tick; what a tick cannot take back is owed by the next. Only the
// translation is watched: the torque is rendered as it is.

#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "client/haptic_loop/surface_sweep.h"
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
  /// Ticks of device and proxy positions kept to match a model with the
  /// pose it was taken at: the longest round trip corrected (2 s at 1 kHz).
  int history_ticks = 2048;
  /// The passivity controller's largest damping, N*s/m; 0 turns it off.
  /// Its force changes by at most max_switch_step_n a tick.
  double max_passivity_damping_ns_per_m = 30;
  /// The work the controller lets the contact hand the hand beyond what
  /// its spring holds, joules.
  double passivity_reserve_j = 2e-4;
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
  explicit HapticLoop(const HapticLoopOptions& options = {});

  /// Renders from `model` from the next tick on. A model with a number that
  /// is not finite, a normal that is not unit, or a radius or clamp that is
  /// not > 0 is rejected (false; the last model stays). A model of the
  /// revision the loop has (LocalModel::revision, not 0) is taken as it.
  bool SetModel(const LocalModel& model);

  /// One tick with the device at X_WD (world frame, metres). A non-finite
  /// pose returns the last output unchanged (counted).
  HapticOutput Tick(const Isometry3d& X_WD);

  bool has_model() const { return has_model_ || has_pending_model_; }
  /// Models and poses rejected so far.
  int64_t rejected_models() const { return rejected_models_; }
  int64_t rejected_poses() const { return rejected_poses_; }
  /// Models whose device pose was not among the last ticks' (the proxy
  /// restarted at the server's).
  int64_t restarted_models() const { return restarted_models_; }
  /// Ticks whose device lay past the model's validity radius.
  int64_t beyond_validity_ticks() const { return beyond_validity_ticks_; }
  /// Ticks the passivity controller added damping on, and the work it took
  /// back from the hand, joules.
  int64_t passivity_ticks() const { return passivity_ticks_; }
  double passivity_dissipated_j() const { return passivity_dissipated_j_; }

 private:
  // MoveProxy moves proxy_ toward `target` against the model's planes or
  // surface, sliding toward it (with the model's friction if `friction`);
  // it returns what it last touched. The proxy may leave the validity
  // sphere (it is rendered at the sphere's edge): it is the loop's
  // reckoning of where the server's proxy would be, which the next model
  // corrects (on planes) or restarts (on a surface, when it lies in a face).
  // What the proxy meets: a plane of the model, or a face of its surface
  // (index -1: nothing), where along the move (0..1), its normal and its
  // material.
  struct Meet {
    int index = -1;
    double t = std::numeric_limits<double>::infinity();
    Vector3d normal = Vector3d::Zero();
    ModelMaterial material;
  };
  Meet MoveProxy(const Vector3d& target, bool friction);
  // The first plane or face the straight move from `p` by `v` meets.
  Meet FirstMeet(const Vector3d& p, const Vector3d& v) const;
  // The first plane the straight move from `p` by `v` meets, and where
  // along it (0..1); plane -1 for none.
  struct Hit {
    int plane = -1;
    double t = std::numeric_limits<double>::infinity();
  };
  Hit FirstHit(const Vector3d& p, const Vector3d& v) const;
  // Whether the tool at `p` has slid off separating plane `plane`'s face:
  // it is in front of another separating plane of the same object.
  bool LeftPlane(const Vector3d& p, int plane) const;
  // Where the model holds: the surface's sphere when the loop renders
  // from the surface, else the model's validity sphere about its proxy.
  struct Sphere {
    Vector3d center;
    double radius;
  };
  Sphere ValiditySphere() const;
  // How far in front of what it meets the proxy stops, metres.
  double StandOff() const;
  // The point of the validity sphere nearest `point`.
  Vector3d InValidity(const Vector3d& point) const;
  // Turns the surface's tool to R_WT, if it is not already.
  void Orient(const Matrix3d& R_WT);
  // Makes model_ the pending model: the proxy moves from the new model's
  // proxy toward where the loop's own proxy (at `kept` now, with the device
  // at `device`) would be by the server's reckoning. `kept` is a copy: the
  // caller's is often proxy_ itself.
  void SwitchModel(const Vector3d& device, Vector3d kept);
  // The history entry whose device position is `p_WD`, newest first; -1 for
  // none.
  int FindInHistory(const Vector3d& p_WD) const;
  void Record(const Vector3d& device, const Vector3d& proxy);
  // One tick's proxy move and force against model_.
  HapticOutput Step(const Vector3d& device, const Vector3d& v_WD);
  // The force of touching `touched` with the device at `device` moving
  // at `v_WD`, the proxy at proxy_ or, past the validity sphere, at its
  // edge; `held`: the proxy is past it (normal push only).
  HapticOutput Render(const Meet& touched, const Vector3d& device, const Vector3d& v_WD,
                      bool held) const;
  // The passivity controller: adds to `out` the damping against `v_WD`
  // that keeps the work done on the hand within what the contact may hand
  // back, if the hand goes on at `v_WD` over the next tick.
  void KeepPassive(HapticOutput& out, const Vector3d& v_WD);

  HapticLoopOptions options_;
  LocalModel model_;
  bool has_model_ = false;
  // The model SetModel took, rendered from the next tick.
  LocalModel pending_model_;
  bool has_pending_model_ = false;
  // The surface the loop renders from (model_.surface when on_surface_),
  // held in the sweep, turned to the device's last orientation.
  bool on_surface_ = false;
  std::shared_ptr<const ModelSurface> surface_;
  SurfaceSweep sweep_;
  bool oriented_ = false;
  Matrix3d oriented_to_ = Matrix3d::Identity();
  Matrix3d last_orientation_ = Matrix3d::Identity();
  Vector3d proxy_ = Vector3d::Zero();
  Vector3d last_device_ = Vector3d::Zero();
  bool has_last_device_ = false;
  // The last ticks' device and proxy positions, a ring: entry
  // (history_next_ - 1 - k) mod size is k ticks old.
  struct Rendered {
    Vector3d device;
    Vector3d proxy;
  };
  std::vector<Rendered> history_;
  int history_next_ = 0;
  int history_size_ = 0;
  // What a model switch left to spread over the next ticks, newtons, and
  // the force the last tick's model rendered before it and the passivity
  // controller's damping.
  Vector3d switch_offset_ = Vector3d::Zero();
  Vector3d last_rendered_ = Vector3d::Zero();
  HapticOutput last_;
  int64_t rejected_models_ = 0;
  int64_t rejected_poses_ = 0;
  int64_t beyond_validity_ticks_ = 0;
  int64_t restarted_models_ = 0;
  // Work the force has done on the hand, joules (negative: the contact
  // took energy from the hand), never below what the contact may hand
  // back.
  double work_on_hand_j_ = 0;
  // The energy the touched plane's spring holds this tick, joules.
  double stored_j_ = 0;
  // The passivity controller's damping force of the last tick, N.
  Vector3d passivity_force_ = Vector3d::Zero();
  int64_t passivity_ticks_ = 0;
  double passivity_dissipated_j_ = 0;
};

}  // namespace hs

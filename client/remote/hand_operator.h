#pragma once
// A simulated operator: a hand of stated mass, stiffness and damping that
// pulls the device toward a target path and is pushed back by the force the
// device renders, so that an unstable rendering shows as it would in a
// hand (the device bounces, buzzes or kicks).

#include <string>

#include "absl/status/statusor.h"
#include "common/core/types.h"

namespace hs::cli {

enum class OperatorMotion {
  /// Down by `depth_m` over 0.5 s (a raised cosine), held 0.5 s, back up
  /// over 0.5 s, resting 0.5 s: one press every 2 s.
  kPress,
  /// Down by `depth_m` over 0.5 s, then side to side along world x by
  /// +-`amplitude_m` every 2 s (a sine): sliding with friction.
  kSlide,
  /// Down by `depth_m` and back within 0.1 s, every 0.5 s: a quick tap.
  kTap,
};

/// "press", "slide" or "tap"; INVALID_ARGUMENT otherwise.
absl::StatusOr<OperatorMotion> ParseOperator(const std::string& name);
/// The name ParseOperator reads.
const char* OperatorName(OperatorMotion motion);

struct HandParams {
  /// An arm holding a stylus: about 0.15 kg, 200 N/m and 3 N*s/m (a
  /// relaxed grip; firmer grips are stiffer and damp more).
  double mass_kg = 0.15;
  double stiffness_n_per_m = 200;
  double damping_ns_per_m = 3;
  /// How far the target goes down and sideways, metres.
  double depth_m = 0.02;
  double amplitude_m = 0.03;
};

class HandOperator {
 public:
  /// The hand holds the device at `start` (world frame, metres), at rest.
  HandOperator(OperatorMotion motion, const HandParams& params, const Isometry3d& start);

  /// Where the hand wants the device at `t_s`, world frame, metres.
  Vector3d Target(double t_s) const;
  /// The device pose now: the start's orientation at the hand's position.
  Isometry3d DevicePose() const;
  /// Moves the hand over `dt_s` from `t_s` under the pull toward the target
  /// and `force_W` (the force the device renders, N, world frame): the
  /// work that force does on the hand is added to work_j().
  void Step(double t_s, double dt_s, const Vector3d& force_W);

  /// Work done on the hand by the rendered force so far, joules.
  double work_j() const { return work_j_; }

 private:
  OperatorMotion motion_;
  HandParams params_;
  Isometry3d start_;
  Vector3d x_, v_ = Vector3d::Zero();
  double work_j_ = 0;
};

}  // namespace hs::cli

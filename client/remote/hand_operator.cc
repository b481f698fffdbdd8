#include "client/remote/hand_operator.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace hs::cli {
namespace {

// 0 at u <= 0, 1 at u >= 1, a raised cosine between.
double Ease(double u) {
  u = std::clamp(u, 0.0, 1.0);
  return 0.5 - 0.5 * std::cos(std::numbers::pi * u);
}

}  // namespace

absl::StatusOr<OperatorMotion> ParseOperator(const std::string& name) {
  if (name == "press") return OperatorMotion::kPress;
  if (name == "slide") return OperatorMotion::kSlide;
  if (name == "tap") return OperatorMotion::kTap;
  return absl::InvalidArgumentError("operator must be press, slide or tap, not '" + name + "'");
}

const char* OperatorName(OperatorMotion motion) {
  switch (motion) {
    case OperatorMotion::kPress:
      return "press";
    case OperatorMotion::kSlide:
      return "slide";
    case OperatorMotion::kTap:
      return "tap";
  }
  return "?";
}

HandOperator::HandOperator(OperatorMotion motion, const HandParams& params, const Isometry3d& start)
    : motion_(motion), params_(params), start_(start), x_(start.translation()) {}

Vector3d HandOperator::Target(double t_s) const {
  Vector3d offset = Vector3d::Zero();
  switch (motion_) {
    case OperatorMotion::kPress: {
      const double u = std::fmod(t_s, 2.0);
      offset.z() = -params_.depth_m * (u < 1 ? Ease(u / 0.5) : 1 - Ease((u - 1) / 0.5));
      break;
    }
    case OperatorMotion::kSlide:
      offset.z() = -params_.depth_m * Ease(t_s / 0.5);
      if (t_s > 0.5) offset.x() = params_.amplitude_m * std::sin(std::numbers::pi * (t_s - 0.5));
      break;
    case OperatorMotion::kTap: {
      const double u = std::fmod(t_s, 0.5);
      offset.z() = -params_.depth_m * (u < 0.05 ? Ease(u / 0.05) : 1 - Ease((u - 0.05) / 0.05));
      break;
    }
  }
  return start_.translation() + offset;
}

Isometry3d HandOperator::DevicePose() const {
  Isometry3d X = start_;
  X.translation() = x_;
  return X;
}

void HandOperator::Step(double t_s, double dt_s, const Vector3d& force_W) {
  // Semi-implicit Euler: stable here (the stiffest contact with the hand,
  // about 1,500 N/m on 0.15 kg, gives w dt = 0.1 at 1 kHz).
  const Vector3d pull =
      params_.stiffness_n_per_m * (Target(t_s) - x_) - params_.damping_ns_per_m * v_;
  v_ += (pull + force_W) / params_.mass_kg * dt_s;
  const Vector3d moved = v_ * dt_s;
  work_j_ += force_W.dot(moved);
  x_ += moved;
}

}  // namespace hs::cli

#pragma once
// A scored training exercise, checked and in the world frame: what the
// scorer (scorer.h) measures a trainee's tool against. Plain data; read
// from a haptics.v1.ExerciseSpec by common/api/exercise_file.h.

#include <optional>
#include <string>
#include <vector>

#include "common/core/types.h"

namespace hs {

/// A ball, world frame, metres (the scene's fixed objects do not move).
struct Ball {
  Vector3d center_W = Vector3d::Zero();
  double radius_m = 0;
  bool Contains(const Vector3d& p_W) const { return (p_W - center_W).norm() <= radius_m; }
};

struct Target {
  std::string name;
  std::string object;
  Ball region;
  double min_force_n = 0;
  /// Infinity for no upper bound.
  double max_force_n = 0;
  double hold_s = 0;
};

struct Forbidden {
  std::string object;
  /// None: the whole object.
  std::optional<Ball> region{};
};

struct ForceLimit {
  std::string object;
  double limit_n = 0;
};

/// The score's parts' weights, each >= 0, their sum > 0.
struct ScoreWeights {
  double targets = 50;
  double time = 10;
  double economy = 10;
  double force = 15;
  double forbidden = 10;
  double smoothness = 5;
};

struct Exercise {
  std::string name;
  std::string tool;
  std::vector<Target> targets;  // at least one, in order
  std::vector<Forbidden> forbidden;
  std::vector<ForceLimit> force_limits;
  double time_limit_s = 0;
  ScoreWeights weights;
  /// The tool's position in the scene, world frame, metres: the
  /// exercise's clock starts at the first frame whose device has left it,
  /// so a recording or a live scene that idles first is scored from the
  /// trainee's first motion. None: from the first frame.
  std::optional<Vector3d> tool_home_W;
};

}  // namespace hs

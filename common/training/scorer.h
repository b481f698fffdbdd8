#pragma once
// Scores a trainee's tool through an exercise (exercise.h), one frame at a
// time, the same whichever way the frames come: live from a server, from a
// recording, or simulated offline along a device path. No gRPC, no
// protobuf: callers turn their frames into ScoringFrames.
//
// Rules (docs/training.md states them with the score's formula):
// - a target is reached when the tool has touched its object inside its
//   ball, with a force in its range, for its hold time without a break;
//   targets count in order only;
// - a contact with a forbidden object (inside its ball, when it has one)
//   is an error: each run of frames in such contact counts once, with its
//   duration and largest force;
// - pressing an object with a limit harder than the limit counts its time
//   and the impulse beyond the limit;
// - path length, largest force and jerk are the device's; frames past the
//   time limit are not scored;
// - a run's times (its start, holds, durations, the limit, the jerk's
//   derivatives) are on the device's own clock of the poses applied when
//   the frames carry it, so that a path scores the same whichever delays
//   brought its poses to the steps they were applied at; else on the
//   frames' simulated time.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/core/types.h"
#include "common/training/exercise.h"

namespace hs {

/// The grid the device's positions are taken on for the jerk, seconds of
/// its clock.
inline constexpr double kJerkPeriodS = 0.02;

/// One contact of the tool with an object, as a frame reports it.
struct ScoringContact {
  std::string object;
  /// Contact points, world frame, metres.
  std::vector<Vector3d> points_W{};
};

/// What the scorer reads of a step, for the exercise's tool.
struct ScoringFrame {
  /// Simulated time at the end of the step, seconds.
  double time_s = 0;
  /// The device's origin, world frame, metres.
  Vector3d p_WD = Vector3d::Zero();
  /// The device's clock when it sampled p_WD (any epoch), seconds: the
  /// same time is the same pose, however many frames repeat it. None when
  /// the frame does not say (DevicePoseTime).
  std::optional<double> pose_time_s{};
  /// The force on the device, world frame, newtons.
  Vector3d force_W = Vector3d::Zero();
  std::vector<ScoringContact> contacts{};
};

struct TargetResult {
  std::string name;
  bool reached = false;
  /// Since the run's start, seconds on its clock (when reached).
  double reached_at_s = 0;
  /// The largest force while touching it, newtons.
  double max_force_n = 0;
};

struct ForbiddenContact {
  std::string object;
  double start_s = 0;
  double duration_s = 0;
  double max_force_n = 0;
};

/// One scored frame, for a report's plots.
struct TracePoint {
  double t_s = 0;  // since the run's start, seconds on its clock
  double force_n = 0;
  /// The limit of the object pressed then (0: none).
  double limit_n = 0;
  Vector3d p_WD = Vector3d::Zero();
};

struct ScoreSummary {
  double score = 0;  // 0-100
  bool completed = false;
  double duration_s = 0;
  int targets_reached = 0;
  int targets = 0;
  double path_length_m = 0;
  /// Path length over the shortest path from the start through the targets'
  /// centres (>= 1 for a path through them; 0 before the tool moved).
  double economy = 0;
  double max_force_n = 0;
  double force_limit_exceeded_s = 0;
  double excess_impulse_ns = 0;
  int forbidden_contacts = 0;
  /// RMS of the device's jerk, m/s^3: six times the third divided
  /// difference of its positions on a grid of kJerkPeriodS (the first pose
  /// at or after each grid time), over the device's clock (over the
  /// frames' times when they carry none).
  double jerk_rms = 0;
  std::vector<TargetResult> target_results;
  std::vector<ForbiddenContact> forbidden_list;
};

/// Where a trainee stands now (for live progress).
struct ScoreProgress {
  int current_target = 0;  // 0-based; == targets when all are reached
  double force_n = 0;
  /// The limit of the object the tool presses now (0: none).
  double limit_n = 0;
  int errors = 0;  // forbidden contacts so far
  double elapsed_s = 0;
};

/// A pose's time from a device's clock in nanoseconds (ToolPose's
/// device_time_ns): none for 0, what a device that does not stamp its poses
/// sends.
std::optional<double> DevicePoseTime(int64_t device_time_ns);

class Scorer {
 public:
  explicit Scorer(Exercise exercise);

  /// Scores the next frame (times must not decrease); ignored once done.
  void Add(const ScoringFrame& frame);
  /// The last target was reached, or the time limit passed.
  bool done() const;
  ScoreProgress progress() const;
  ScoreSummary Summary() const;
  /// Every scored frame, in order.
  const std::vector<TracePoint>& trace() const { return trace_; }
  const Exercise& exercise() const { return exercise_; }

 private:
  bool Touches(const ScoringFrame& frame, const std::string& object, const Ball* region) const;
  void ScoreTargets(const ScoringFrame& frame, double force, double dt);
  void ScoreForbidden(const ScoringFrame& frame, double force, double dt);
  void ScoreLimits(const ScoringFrame& frame, double force, double dt);
  void SampleMotion(double t, const Vector3d& p);
  void SampleJerk(double t, const Vector3d& p);

  // A pose taken for the jerk: its time and the device's origin.
  struct Sample {
    double t = 0;
    Vector3d p = Vector3d::Zero();
  };

  Exercise exercise_;
  bool started_ = false;
  bool timed_out_ = false;
  double start_s_ = 0;
  double last_s_ = 0;

  // A run is timed by one clock: the device's when its first scored frame
  // carries a pose time, else the frames'. start_s_ and last_s_ are on it.
  bool device_clock_ = false;
  // The device's last pose and its time, for the path.
  Vector3d last_p_ = Vector3d::Zero();
  double last_pose_t_ = 0;
  bool has_last_p_ = false;
  // The jerk's grid: from the first pose, kJerkPeriodS apart; the next
  // grid time a pose is taken at or after.
  double jerk_grid_t0_ = 0;
  double next_jerk_t_ = 0;
  // The last four poses taken for the jerk, newest last.
  std::vector<Sample> recent_;
  Vector3d start_p_ = Vector3d::Zero();
  double jerk_sum_sq_ = 0;
  int64_t jerk_samples_ = 0;
  double path_m_ = 0;
  double max_force_ = 0;
  double force_now_ = 0;
  double limit_now_ = 0;
  double exceeded_s_ = 0;
  double excess_ns_ = 0;
  int current_ = 0;
  // The current target: touched in range at the last frame, and for how long.
  bool holding_ = false;
  double held_s_ = 0;
  double finished_at_s_ = -1;
  std::vector<TargetResult> targets_;
  std::vector<TracePoint> trace_;
  std::vector<ForbiddenContact> forbidden_;
  // Per forbidden region: its entry in forbidden_ while in contact, else -1.
  std::vector<int> open_forbidden_;
};

}  // namespace hs

#include "common/training/scorer.h"

#include <algorithm>
#include <cmath>

namespace hs {
namespace {

// The score's scales (docs/training.md): an excess impulse of this much
// halves the force part; this much jerk halves the smoothness part.
constexpr double kExcessImpulseScaleNs = 0.1;
constexpr double kJerkScaleMPerS3 = 10;

// Six times the third divided difference of four samples: the jerk of the
// cubic through them, exact for a cubic however the samples are spaced.
Vector3d Jerk(const double t[4], const Vector3d p[4]) {
  Vector3d d[4] = {p[0], p[1], p[2], p[3]};
  for (int order = 1; order <= 3; ++order) {
    for (int i = 3; i >= order; --i) d[i] = (d[i] - d[i - 1]) / (t[i] - t[i - order]);
  }
  return 6 * d[3];
}

}  // namespace

std::optional<double> DevicePoseTime(int64_t device_time_ns) {
  if (device_time_ns == 0) return std::nullopt;
  // Divided, not multiplied by 1e-9: a stamp of whole nanoseconds then
  // reads as the seconds it was made from (0.005 s as 0.005).
  return static_cast<double>(device_time_ns) / 1e9;
}

Scorer::Scorer(Exercise exercise)
    : exercise_(std::move(exercise)), open_forbidden_(exercise_.forbidden.size(), -1) {
  for (const Target& t : exercise_.targets) targets_.push_back({.name = t.name});
}

bool Scorer::done() const {
  return timed_out_ || current_ == static_cast<int>(exercise_.targets.size());
}

bool Scorer::Touches(const ScoringFrame& frame, const std::string& object,
                     const Ball* region) const {
  for (const ScoringContact& c : frame.contacts) {
    if (c.object != object) continue;
    if (!region) return true;
    for (const Vector3d& p : c.points_W) {
      if (region->Contains(p)) return true;
    }
  }
  return false;
}

void Scorer::Add(const ScoringFrame& frame) {
  if (done()) return;
  if (!started_) {
    if (exercise_.tool_home_W && frame.p_WD == *exercise_.tool_home_W) return;
    started_ = true;
    device_clock_ = frame.pose_time_s.has_value();
    start_s_ = last_s_ = device_clock_ ? *frame.pose_time_s : frame.time_s;
    start_p_ = frame.p_WD;
  }
  // On the device's clock a frame is as late as the pose it applies, not
  // as late as the network brought that pose to a step; a frame that
  // brings no newer pose adds no time.
  const double t =
      device_clock_ ? std::max(last_s_, frame.pose_time_s.value_or(last_s_)) : frame.time_s;
  if (t - start_s_ > exercise_.time_limit_s) {
    timed_out_ = true;
    return;
  }
  const double dt = std::max(0.0, t - last_s_);
  last_s_ = t;
  SampleMotion(t, frame.p_WD);
  const double force = frame.force_W.norm();
  force_now_ = force;
  max_force_ = std::max(max_force_, force);
  ScoreLimits(frame, force, dt);
  ScoreForbidden(frame, force, dt);
  ScoreTargets(frame, force, dt);
  trace_.push_back({t - start_s_, force, limit_now_, frame.p_WD});
}

void Scorer::SampleMotion(double t, const Vector3d& p) {
  // A time already taken is the same pose again (the device sent none
  // since), or one that came out of order.
  if (has_last_p_ && t <= last_pose_t_) return;
  if (has_last_p_) path_m_ += (p - last_p_).norm();
  last_p_ = p;
  last_pose_t_ = t;
  has_last_p_ = true;
  SampleJerk(t, p);
}

void Scorer::SampleJerk(double t, const Vector3d& p) {
  // On a grid of kJerkPeriodS from the first pose, not every pose: a pose
  // held for a few steps and then moved would read as an enormous jerk at
  // 1 kHz. The first pose at or after each grid time is taken, so a pose
  // the network lost moves one sample only, not every later one.
  if (recent_.empty()) {
    jerk_grid_t0_ = t;
  } else if (t + 1e-9 < next_jerk_t_) {
    return;
  }
  next_jerk_t_ =
      jerk_grid_t0_ + (std::floor((t - jerk_grid_t0_ + 1e-9) / kJerkPeriodS) + 1) * kJerkPeriodS;
  recent_.push_back({t, p});
  if (recent_.size() > 4) recent_.erase(recent_.begin());
  if (recent_.size() < 4) return;
  const double ts[4] = {recent_[0].t, recent_[1].t, recent_[2].t, recent_[3].t};
  const Vector3d ps[4] = {recent_[0].p, recent_[1].p, recent_[2].p, recent_[3].p};
  jerk_sum_sq_ += Jerk(ts, ps).squaredNorm();
  ++jerk_samples_;
}

void Scorer::ScoreLimits(const ScoringFrame& frame, double force, double dt) {
  // The strictest limit among the objects pressed now.
  limit_now_ = 0;
  for (const ForceLimit& limit : exercise_.force_limits) {
    if (!Touches(frame, limit.object, nullptr)) continue;
    if (limit_now_ == 0 || limit.limit_n < limit_now_) limit_now_ = limit.limit_n;
  }
  if (limit_now_ > 0 && force > limit_now_) {
    exceeded_s_ += dt;
    excess_ns_ += (force - limit_now_) * dt;
  }
}

void Scorer::ScoreForbidden(const ScoringFrame& frame, double force, double dt) {
  for (size_t i = 0; i < exercise_.forbidden.size(); ++i) {
    const Forbidden& f = exercise_.forbidden[i];
    const bool touching = Touches(frame, f.object, f.region ? &*f.region : nullptr);
    int& open = open_forbidden_[i];
    if (!touching) {
      open = -1;
      continue;
    }
    if (open < 0) {
      open = static_cast<int>(forbidden_.size());
      forbidden_.push_back({.object = f.object, .start_s = last_s_ - start_s_});
    } else {
      forbidden_[open].duration_s += dt;
    }
    forbidden_[open].max_force_n = std::max(forbidden_[open].max_force_n, force);
  }
}

void Scorer::ScoreTargets(const ScoringFrame& frame, double force, double dt) {
  if (current_ >= static_cast<int>(exercise_.targets.size())) return;
  const Target& target = exercise_.targets[current_];
  const bool touching = Touches(frame, target.object, &target.region);
  if (touching) targets_[current_].max_force_n = std::max(targets_[current_].max_force_n, force);
  if (!touching || force < target.min_force_n || force > target.max_force_n) {
    holding_ = false;
    return;
  }
  // The first frame in range starts the hold; each later one adds its step.
  held_s_ = holding_ ? held_s_ + dt : 0;
  holding_ = true;
  if (held_s_ + 1e-9 < target.hold_s) return;
  targets_[current_].reached = true;
  targets_[current_].reached_at_s = last_s_ - start_s_;
  holding_ = false;
  ++current_;
  if (done()) finished_at_s_ = last_s_ - start_s_;
}

ScoreProgress Scorer::progress() const {
  return {.current_target = current_,
          .force_n = force_now_,
          .limit_n = limit_now_,
          .errors = static_cast<int>(forbidden_.size()),
          .elapsed_s = last_s_ - start_s_};
}

ScoreSummary Scorer::Summary() const {
  ScoreSummary s;
  s.targets = static_cast<int>(exercise_.targets.size());
  s.targets_reached = current_;
  s.completed = current_ == s.targets;
  s.duration_s = s.completed ? finished_at_s_ : last_s_ - start_s_;
  s.path_length_m = path_m_;
  double shortest = 0;
  Vector3d from = start_p_;
  for (const Target& t : exercise_.targets) {
    shortest += (t.region.center_W - from).norm();
    from = t.region.center_W;
  }
  s.economy = shortest > 0 ? path_m_ / shortest : 0;
  s.max_force_n = max_force_;
  s.force_limit_exceeded_s = exceeded_s_;
  s.excess_impulse_ns = excess_ns_;
  s.forbidden_contacts = static_cast<int>(forbidden_.size());
  s.jerk_rms = jerk_samples_ > 0 ? std::sqrt(jerk_sum_sq_ / static_cast<double>(jerk_samples_)) : 0;
  s.target_results = targets_;
  s.forbidden_list = forbidden_;

  // Each part in [0, 1], weighed (docs/training.md). How well the work was
  // done counts for the share of it that was done: doing nothing scores 0.
  const ScoreWeights& w = exercise_.weights;
  const double part_targets = static_cast<double>(s.targets_reached) / s.targets;
  const double part_time =
      s.completed ? std::clamp(1 - s.duration_s / exercise_.time_limit_s, 0.0, 1.0) : 0;
  const double part_economy = s.economy > 0 ? std::min(1.0, 1 / s.economy) : 0;
  const double part_force = 1 / (1 + s.excess_impulse_ns / kExcessImpulseScaleNs);
  const double part_forbidden = 1.0 / (1 + s.forbidden_contacts);
  const double part_smooth = 1 / (1 + s.jerk_rms / kJerkScaleMPerS3);
  const double sum = w.targets + w.time + w.economy + w.force + w.forbidden + w.smoothness;
  const double quality = w.time * part_time + w.economy * part_economy + w.force * part_force +
                         w.forbidden * part_forbidden + w.smoothness * part_smooth;
  s.score = 100 * (w.targets * part_targets + part_targets * quality) / sum;
  return s;
}

}  // namespace hs

#pragma once
// Timed device paths for `drive` and `loadtest`: from a file (CSV at a
// rate, or JSON lines with times) or a built-in motion (press, sweep)
// that starts at the tool's pose in the scene.

#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "common/core/types.h"

namespace hs::cli {

/// A device pose X_WD (world frame, metres) and when to send it, seconds
/// after the first.
struct TimedPose {
  double t_s = 0;
  Isometry3d X_WD = Isometry3d::Identity();
};

/// The poses of a path file with their send times. A file ending in
/// ".jsonl" holds one JSON object per line, {"t_s": 0.01, "pose": [x, y,
/// z, rx, ry, rz]} ("t_s" optional: i / rate_hz), after an optional
/// header line (DevicePathScene); any other file is CSV
/// (tool_path.h), pose i sent at i / rate_hz. NOT_FOUND when the file
/// cannot be opened, INVALID_ARGUMENT naming the line otherwise (times
/// must not decrease).
absl::StatusOr<std::vector<TimedPose>> ReadDevicePath(const std::string& path, double rate_hz);

/// The scene a path file says it moves in, "" when it names none: a JSON
/// lines file's header line {"scene": "NAME"} (before its poses), or a
/// CSV comment line "# scene: NAME". NOT_FOUND when it cannot be opened.
absl::StatusOr<std::string> DevicePathScene(const std::string& path);

/// The built-in motions.
enum class Motion {
  /// Straight down (MotionParams::press_direction) by `depth_m` and back,
  /// once a second (a raised cosine), starting at `start`.
  kPress,
  /// Down by `depth_m` over the first 0.25 s, then side to side along
  /// world x by +-`amplitude_m` every 2 s (a sine).
  kSweep,
};

/// "press" or "sweep"; INVALID_ARGUMENT otherwise.
absl::StatusOr<Motion> ParseMotion(const std::string& name);

/// The shape of a built-in motion.
struct MotionParams {
  double depth_m = 0.02;
  /// The way a press goes (unit, world frame): down unless told.
  Vector3d press_direction = -Vector3d::UnitZ();
  double amplitude_m = 0.05;
  /// Seconds added to the motion's clock (a phase, for many devices).
  double phase_s = 0;
};

/// `motion` from `start` sampled at `rate_hz` for `duration_s` seconds:
/// pose i at t = i / rate_hz (the orientation stays `start`'s).
std::vector<TimedPose> MotionPath(Motion motion, const Isometry3d& start, double rate_hz,
                                  double duration_s, const MotionParams& params = {});

/// The offset of `motion` from its start at time `t_s` (world frame, metres).
Vector3d MotionOffset(Motion motion, double t_s, const MotionParams& params);

}  // namespace hs::cli

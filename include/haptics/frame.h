#pragma once
// A frame of a running scene (haptics.v1.Frame) in plain C++ types: what a
// Watcher hands out. Parts a stream did not ask for stay empty or zero.

#include <cstdint>
#include <string>
#include <vector>

#include "haptics/pose.h"

namespace haptics {

/// A tool's contact with one object (the contacts part).
struct Contact {
  std::string object;
  bool colliding = false;
  bool penetrating = false;
  /// How far the tool must move back along -direction_w, metres.
  double depth_m = 0;
  /// Unit, world frame, from the object toward the tool.
  double normal_w[3] = {0, 0, 0};
  /// The contact points, world frame, metres: x, y, z each.
  std::vector<double> points_w_m;
  /// The fraction of the step of the first touch, when continuous
  /// collision found one; else -1.
  double time_of_impact = -1;
};

/// A plane of a local contact model: the tool stays in front of it.
struct Plane {
  std::string object;
  double point_w_m[3] = {0, 0, 0};
  double normal_w[3] = {0, 0, 1};
  double gap_m = 0;
  double stiffness_n_per_m = 0;
  double damping_ns_per_m = 0;
  /// In front of this plane, within the validity radius, the tool meets
  /// nothing of its object (the planes naming it), whatever the object's
  /// other planes say (docs/remote-haptics.md, Separating planes).
  bool separating = false;
};

/// A tool's local contact model (the local model part; docs/remote-haptics.md).
struct LocalModel {
  /// 1 for the tool's first model, +1 per model built; 0 unknown.
  uint64_t revision = 0;
  Pose proxy_pose;
  double validity_radius_m = 0;
  double force_clamp_n = 0;
  bool touching = false;
  std::vector<Plane> planes;
};

struct ToolFrame {
  std::string tool;
  /// Who drives it now; empty when no device holds it.
  std::string holder;
  /// The poses part: the device pose applied and the proxy's.
  Pose device_pose;
  Pose proxy_pose;
  /// The forces part: on the device, world frame, N and N*m.
  double force_n[3] = {0, 0, 0};
  double torque_nm[3] = {0, 0, 0};
  bool force_clamped = false;
  std::vector<Contact> contacts;
  bool has_local_model = false;
  LocalModel local_model;
};

struct Frame {
  /// 1 for the scene's first step, +1 per step.
  int64_t step = 0;
  /// Simulated time at the end of the step, seconds.
  double time_s = 0;
  /// Frames this stream missed by reading too slowly, since it began.
  uint64_t dropped_frames = 0;
  /// Steps the scene started late, since it began.
  int64_t missed_steps = 0;
  std::vector<ToolFrame> tools;
};

}  // namespace haptics

#pragma once
// What one simulation step produces: per tool, the device pose it applied,
// the proxy (god-object) pose, the force, and the contact with each object.

#include <array>
#include <cstdint>
#include <vector>

#include "common/contact/contact_set.h"
#include "common/sim/effects.h"
#include "common/sim/local_model.h"

namespace hs {

/// A scene object's id: its index in the order objects were added.
using ObjectId = int32_t;

/// A tool's contact with one other object at the device pose.
struct PairContact {
  ObjectId object = -1;
  /// The sub-step (1 to ToolFrame::substeps) whose tool pose the contact
  /// is at: the last one (the device pose) when the pair touches there,
  /// else the first that touched (the tool passed through).
  int substep = 1;
  /// Filled as far as the stages that ran allow: `colliding` by collision,
  /// features and normal by the contact set, depth and reversing vector by
  /// the reversing-vector stage.
  ContactSet contact;
};

struct ToolFrame {
  ObjectId tool = -1;
  /// The device pose applied this step, world frame, metres.
  Isometry3d X_WD = Isometry3d::Identity();
  /// The proxy (god-object) pose: the device pose kept out of the objects,
  /// world frame, metres. Equal to X_WD when nothing is touched.
  Isometry3d X_WP = Isometry3d::Identity();
  /// Force and torque on the device (to render), world frame, N and N*m;
  /// the torque about the device origin, its lever the tool-fixed one from
  /// the proxy's origin to the touching point (tool_force.h). Zero unless
  /// the force stage ran.
  Vector3d force_W = Vector3d::Zero();
  Vector3d torque_W = Vector3d::Zero();
  /// The force was limited to the scene's clamp.
  bool force_clamped = false;
  /// How many sub-steps the collision stage split the device's motion
  /// into: more than 1 when, without continuous collision, the tool moved
  /// farther than the shortest box edge of itself and the objects its
  /// swept box meets (paper s.4, fig. 3 c).
  int substeps = 1;
  /// One entry per object the tool touches or penetrates, by object id.
  std::vector<PairContact> contacts;
  /// The tool whose proxy this tool's proxy rests on, when the proxy stage
  /// ran (-1 for none): a clash also when no stage lists contacts.
  ObjectId touched_tool = -1;
  /// The local contact model at the proxy pose, when the local-model stage
  /// ran (else its planes are empty and its radius 0).
  LocalModel local_model;
};

/// Where a free body ended a step.
struct BodyFrame {
  ObjectId body = -1;
  /// X_WO at the end of the step, world frame, metres.
  Isometry3d X_WO = Isometry3d::Identity();
  /// Velocity of the centre of mass and angular velocity, world frame, m/s
  /// and rad/s.
  Vector3d v_W = Vector3d::Zero();
  Vector3d w_W = Vector3d::Zero();
  /// Contacts resolved this step (one per object per sub-step).
  int contacts = 0;
  /// The objects it touched this step (in any sub-step), ascending, each
  /// once: tools among them hold it when nothing else touches it.
  std::vector<ObjectId> touching;
  /// Sub-steps the body's motion was split into (1: not split).
  int substeps = 1;
};

/// Two tools' clashes (their contacts with each other), since the scene
/// began: a laparoscopic trainer counts each as an error.
struct ToolClash {
  /// The two tools, tool_a < tool_b.
  ObjectId tool_a = -1;
  ObjectId tool_b = -1;
  /// How many times they began to touch, and for how long they touched
  /// (steps times the step's length), seconds.
  int64_t count = 0;
  double seconds = 0;
  /// Whether they touch at this step, and began to at it.
  bool touching = false;
  bool began = false;
};

struct StepFrame {
  /// 1 for the first step, then +1 per step.
  int64_t step = 0;
  /// Simulated time at the end of the step, seconds.
  double time_s = 0;
  /// The stages that ran this step.
  EffectSet stages_run;
  /// One entry per tool, by tool id.
  std::vector<ToolFrame> tools;
  /// One entry per free body, by id.
  std::vector<BodyFrame> bodies;
  /// Every tool pair that ever touched, by (tool_a, tool_b); counted from
  /// the tools' contacts and proxies.
  std::vector<ToolClash> clashes;
};

/// How often and how long one stage ran, since the scene was created.
/// Continuous collision and friction run inside the collision and proxy
/// (reversing-vector) stages: their time is counted there.
struct StageStats {
  int64_t runs = 0;
  int64_t total_ns = 0;
};
using StageStatsTable = std::array<StageStats, kNumEffects>;

}  // namespace hs

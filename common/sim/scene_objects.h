#pragma once
// The posed-object index of a scene: every object with its HDS, hierarchy,
// kind and pose, the broad phase over them, and the views the stages walk
// each step (the fixed objects the proxy keeps out of; the fixed objects
// and free bodies a tool's contacts are reported with, and their boxes),
// kept up to date as objects are added and moved rather than rebuilt per
// step.

#include <limits>
#include <memory>
#include <utility>
#include <vector>

#include "common/collision/broad_phase.h"
#include "common/collision/collision_model.h"
#include "common/contact/contact_query.h"
#include "common/sim/step_frame.h"

namespace hs {

enum class ObjectKind {
  kFixed,  ///< Never moves.
  kTool,   ///< Posed by a device before each step.
  kFree,   ///< Moved by the simulation (free-body motion), pushed by the others.
};

class SceneObjects {
 public:
  struct Object {
    HapticObject object;
    CollisionModel model;
    ObjectKind kind;
    /// Where the object is: fixed objects where added, free bodies as of
    /// their last move, tools where added (their device and proxy poses
    /// are the tool stage's).
    Isometry3d X_WO;
  };

  /// Adds `object` (its hierarchy `model`) at X_WO and returns its id, the
  /// count of objects before it.
  ObjectId Add(HapticObject object, CollisionModel model, ObjectKind kind, const Isometry3d& X_WO);

  /// Moves a free body to X_WO: its pose, target entry, box and broad-phase
  /// entry.
  void MoveBody(ObjectId id, const Isometry3d& X_WO);
  /// Poses a tool in the broad phase (at its device pose).
  void PoseTool(ObjectId id, const Isometry3d& X_WD) { broad_phase_.SetPose(id, X_WD); }
  /// Fills `pairs` with the broad phase's pairs at the current poses.
  void FindCandidatePairs(std::vector<std::pair<ObjectId, ObjectId>>& pairs) const;

  int size() const { return static_cast<int>(objects_.size()); }
  const Object& operator[](ObjectId id) const { return *objects_[id]; }
  PosedObject Posed(ObjectId id, const Isometry3d& X_WO) const {
    const Object& o = *objects_[id];
    return {&o.object, &o.model, X_WO};
  }

  /// The fixed objects, posed, and their ids, in id order.
  const std::vector<PosedObject>& obstacles() const { return obstacles_; }
  const std::vector<ObjectId>& obstacle_ids() const { return obstacle_ids_; }
  /// The fixed objects and free bodies, posed, their ids and their world
  /// boxes grown by their models' margins, in id order.
  const std::vector<PosedObject>& targets() const { return targets_; }
  const std::vector<ObjectId>& target_ids() const { return target_ids_; }
  const std::vector<AlignedBox3d>& target_boxes() const { return target_boxes_; }
  /// The index of object `id` in targets(); -1 for tools.
  int target_index(ObjectId id) const { return target_index_[id]; }
  /// The world box of object `id` at X_WO grown by its model's margin.
  AlignedBox3d GrownBox(ObjectId id, const Isometry3d& X_WO) const;
  /// The shortest bounding-box edge of any object, metres (+inf when none).
  double smallest_edge_m() const { return smallest_edge_m_; }

 private:
  std::vector<std::unique_ptr<Object>> objects_;
  std::vector<PosedObject> obstacles_;
  std::vector<ObjectId> obstacle_ids_;
  std::vector<PosedObject> targets_;
  std::vector<ObjectId> target_ids_;
  std::vector<AlignedBox3d> target_boxes_;
  std::vector<int> target_index_;
  double smallest_edge_m_ = std::numeric_limits<double>::infinity();
  BroadPhase broad_phase_;
};

}  // namespace hs

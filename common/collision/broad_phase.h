#pragma once
// Broad phase over all objects of a scene: which object pairs are close
// enough to need the triangle test. FCL's dynamic AABB tree manager.

#include <memory>
#include <utility>
#include <vector>

#include "common/collision/collision_model.h"

namespace hs {

class BroadPhase {
 public:
  /// The caller's name for an object (its scene object id).
  using Key = int32_t;

  BroadPhase();
  ~BroadPhase();
  BroadPhase(const BroadPhase&) = delete;
  BroadPhase& operator=(const BroadPhase&) = delete;

  /// Adds `model` posed at X_WO (world frame, metres) under `key`, replacing
  /// what `key` held. The broad phase shares the model's hierarchy, so a
  /// later CollisionModel::Sync is seen after the next SetPose of that key.
  void Add(Key key, const CollisionModel& model, const Isometry3d& X_WO);
  /// Removes `key`; no effect when absent.
  void Remove(Key key);
  /// Moves `key` to X_WO. The key must have been added.
  void SetPose(Key key, const Isometry3d& X_WO);

  /// Fills `pairs` with the object pairs (first < second, sorted) whose
  /// world boxes, grown by the models' margins, overlap; what it held goes
  /// (its capacity stays, so a step reusing it allocates nothing).
  void CandidatePairs(std::vector<std::pair<Key, Key>>& pairs) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace hs

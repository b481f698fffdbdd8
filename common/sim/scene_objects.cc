#include "common/sim/scene_objects.h"

#include <algorithm>

#include "common/sim/motion_bounds.h"

namespace hs {

ObjectId SceneObjects::Add(HapticObject object, CollisionModel model, ObjectKind kind,
                           const Isometry3d& X_WO) {
  const auto id = static_cast<ObjectId>(objects_.size());
  smallest_edge_m_ = std::min(smallest_edge_m_, object.smallest_box_edge());
  objects_.push_back(
      std::make_unique<Object>(Object{std::move(object), std::move(model), kind, X_WO}));
  const Object& added = *objects_.back();
  broad_phase_.Add(id, added.model, X_WO);
  if (kind == ObjectKind::kTool) {
    target_index_.push_back(-1);
    return id;
  }
  if (kind == ObjectKind::kFixed) {
    obstacles_.push_back(Posed(id, X_WO));
    obstacle_ids_.push_back(id);
  }
  target_index_.push_back(static_cast<int>(targets_.size()));
  targets_.push_back(Posed(id, X_WO));
  target_ids_.push_back(id);
  target_boxes_.push_back(GrownBox(id, X_WO));
  return id;
}

void SceneObjects::MoveBody(ObjectId id, const Isometry3d& X_WO) {
  objects_[id]->X_WO = X_WO;
  const int k = target_index_[id];
  targets_[k].X_WO = X_WO;
  target_boxes_[k] = GrownBox(id, X_WO);
  broad_phase_.SetPose(id, X_WO);
}

void SceneObjects::FindCandidatePairs(std::vector<std::pair<ObjectId, ObjectId>>& pairs) const {
  broad_phase_.CandidatePairs(pairs);
}

AlignedBox3d SceneObjects::GrownBox(ObjectId id, const Isometry3d& X_WO) const {
  const Object& o = *objects_[id];
  return GrowBox(WorldBox(o.object, X_WO), o.model.margin_m());
}

}  // namespace hs

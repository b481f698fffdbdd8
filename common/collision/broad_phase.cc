#include "common/collision/broad_phase.h"

#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/narrowphase/collision_object.h>

#include <algorithm>
#include <map>

#include "common/collision/fcl_bvh.h"
#include "common/core/check.h"

namespace hs {

struct BroadPhase::Impl {
  fcl::DynamicAABBTreeCollisionManagerd manager;
  std::map<Key, std::unique_ptr<fcl::CollisionObjectd>> objects;
};

namespace {

// FCL carries the caller's key in the object's user-data pointer.
void* KeyToUserData(BroadPhase::Key key) {
  return reinterpret_cast<void*>(static_cast<intptr_t>(key));
}
BroadPhase::Key UserDataToKey(void* data) {
  return static_cast<BroadPhase::Key>(reinterpret_cast<intptr_t>(data));
}

}  // namespace

BroadPhase::BroadPhase() : impl_(std::make_unique<Impl>()) {}
BroadPhase::~BroadPhase() = default;

void BroadPhase::Add(Key key, const CollisionModel& model, const Isometry3d& X_WO) {
  Remove(key);
  auto object = std::make_unique<fcl::CollisionObjectd>(model.impl().geometry(), X_WO);
  object->setUserData(KeyToUserData(key));
  impl_->manager.registerObject(object.get());
  impl_->objects[key] = std::move(object);
  impl_->manager.update();
}

void BroadPhase::Remove(Key key) {
  auto it = impl_->objects.find(key);
  if (it == impl_->objects.end()) return;
  impl_->manager.unregisterObject(it->second.get());
  impl_->objects.erase(it);
}

void BroadPhase::SetPose(Key key, const Isometry3d& X_WO) {
  auto it = impl_->objects.find(key);
  HS_CHECK(it != impl_->objects.end());
  it->second->setTransform(X_WO);
  it->second->computeAABB();
  impl_->manager.update(it->second.get());
}

void BroadPhase::CandidatePairs(std::vector<std::pair<Key, Key>>& pairs) const {
  pairs.clear();
  impl_->manager.collide(
      &pairs, [](fcl::CollisionObjectd* o1, fcl::CollisionObjectd* o2, void* data) {
        auto& out = *static_cast<std::vector<std::pair<Key, Key>>*>(data);
        const Key k1 = UserDataToKey(o1->getUserData()), k2 = UserDataToKey(o2->getUserData());
        out.emplace_back(std::min(k1, k2), std::max(k1, k2));
        return false;  // never stop early: we want every pair
      });
  std::sort(pairs.begin(), pairs.end());
}

}  // namespace hs

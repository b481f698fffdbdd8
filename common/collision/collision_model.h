#pragma once
// The bounding volume hierarchy (FCL BVH) of one HDS object, in the object's
// own frame. Face i of the object is triangle i of the hierarchy.

#include <memory>

#include "common/collision/bv_type.h"
#include "common/hds/haptic_object.h"

namespace hs {

class CollisionModel {
 public:
  /// Builds the hierarchy of `object`'s faces. Every bounding volume is
  /// grown by `margin_m` (metres, >= 0) so that pairs closer than the margin
  /// reach the triangle test: touching contacts are not lost to rounding.
  CollisionModel(const HapticObject& object, BvType type, double margin_m);
  ~CollisionModel();
  CollisionModel(CollisionModel&&) noexcept;
  CollisionModel& operator=(CollisionModel&&) noexcept;

  BvType bv_type() const;
  double margin_m() const;
  /// The object's geometry version the hierarchy was built or refitted at.
  uint64_t geometry_version() const;

  /// Refits the volumes to `object` (the object it was built from, with
  /// moved vertices) when its geometry version differs from ours. Returns
  /// whether it refitted. Topology never changes, so no rebuild is needed.
  bool Sync(const HapticObject& object);

  /// FCL types stay behind this: defined in fcl_bvh.h, used only by
  /// common/collision.
  struct Impl;
  const Impl& impl() const { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace hs

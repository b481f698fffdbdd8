#include "common/collision/faces_in_box.h"

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/utility.h>

#include "common/collision/fcl_bvh.h"
#include "common/collision/obb_overlap.h"
#include "common/core/scratch.h"

namespace hs {
namespace {

// The traversal's stack of node indices, kept between queries.
struct NodeStack {
  std::vector<int> nodes;
};

// A box (half sides `half`, pose X_OB in the object frame) as a query on
// volumes of kind BV. Volumes with an oriented culling box (OBB, OBBRSS)
// are tested against the box itself, with the pair traversal's lean test
// (obb_overlap.h: a bounding-sphere test first); the other kinds against
// FCL's conversion of it, which allocates.
template <typename BV>
class BoxQuery {
 public:
  BoxQuery(const Vector3d& half, const fcl::Transform3d& X_OB) {
    box_ = {
        .axis = X_OB.linear(), .center = X_OB.translation(), .extent = half, .radius = half.norm()};
    if constexpr (!kOriented) fcl::computeBV(fcl::Boxd(2 * half), X_OB, converted_);
  }
  bool Meets(const BV& node) const {
    if constexpr (kOriented) {
      const fcl::OBBd& volume = CullingBox(node);
      return !BoxesDisjoint(volume, volume.extent.norm(), box_);
    } else {
      return node.overlap(converted_);
    }
  }

 private:
  static constexpr bool kOriented = requires(const BV& bv) { CullingBox(bv); };
  PlacedBox box_;
  BV converted_;
};

template <typename BV>
void FindFacesInBox(const fcl::BVHModel<BV>& bvh, const std::vector<uint8_t>& degenerate,
                    const Isometry3d& X_OW, const AlignedBox3d& box_W, std::vector<FaceId>& faces) {
  // The box in the object frame, tested against each node's volume.
  fcl::Transform3d X_OB = X_OW;
  X_OB.translation() = X_OW * box_W.center();
  const BoxQuery<BV> query(box_W.sizes() / 2, X_OB);
  std::vector<int>& stack = Scratch<NodeStack>().nodes;
  stack.assign(1, 0);
  while (!stack.empty()) {
    const fcl::BVNode<BV>& node = bvh.getBV(stack.back());
    stack.pop_back();
    if (!query.Meets(node.bv)) continue;
    if (node.isLeaf()) {
      if (!degenerate[node.primitiveId()]) faces.push_back(node.primitiveId());
    } else {
      stack.push_back(node.rightChild());
      stack.push_back(node.leftChild());
    }
  }
}

}  // namespace

void FindFacesInBox(const CollisionModel& model, const Isometry3d& X_WO, const AlignedBox3d& box_W,
                    std::vector<FaceId>& faces) {
  const CollisionModel::Impl& impl = model.impl();
  if (box_W.isEmpty()) return;
  std::visit(
      [&](const auto& bvh) {
        if (bvh->getNumBVs() > 0) {
          FindFacesInBox(*bvh, impl.degenerate, X_WO.inverse(), box_W, faces);
        }
      },
      impl.bvh);
}

}  // namespace hs

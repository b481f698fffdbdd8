#include "common/collision/faces_in_box.h"

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/utility.h>

#include "common/collision/fcl_bvh.h"
#include "common/core/scratch.h"

namespace hs {
namespace {

// The traversal's stack of node indices, kept between queries.
struct NodeStack {
  std::vector<int> nodes;
};

template <typename BV>
void FindFacesInBox(const fcl::BVHModel<BV>& bvh, const std::vector<uint8_t>& degenerate,
                    const Isometry3d& X_OW, const AlignedBox3d& box_W, std::vector<FaceId>& faces) {
  // The box as a volume of the hierarchy's own kind, in the object frame,
  // so that FCL's same-kind overlap test decides each node.
  const fcl::Boxd box(box_W.sizes());
  fcl::Transform3d X_OB = X_OW;
  X_OB.translation() = X_OW * box_W.center();
  BV query;
  fcl::computeBV(box, X_OB, query);
  std::vector<int>& stack = Scratch<NodeStack>().nodes;
  stack.assign(1, 0);
  while (!stack.empty()) {
    const fcl::BVNode<BV>& node = bvh.getBV(stack.back());
    stack.pop_back();
    if (!node.bv.overlap(query)) continue;
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

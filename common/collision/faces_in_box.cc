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

// A box (half sides `half`, pose X_OB in the object frame) as a query on
// volumes of kind BV. Oriented boxes (OBB, and OBBRSS by its box) test the
// box itself; the other kinds take FCL's conversion, which allocates.
template <typename BV>
class BoxQuery {
 public:
  BoxQuery(const Vector3d& half, const fcl::Transform3d& X_OB) {
    fcl::computeBV(fcl::Boxd(2 * half), X_OB, bv_);
  }
  bool Meets(const BV& node) const { return node.overlap(bv_); }

 private:
  BV bv_;
};

fcl::OBBd OrientedBox(const Vector3d& half, const fcl::Transform3d& X_OB) {
  fcl::OBBd box;
  box.axis = X_OB.linear();
  box.To = X_OB.translation();
  box.extent = half;
  return box;
}

template <>
class BoxQuery<fcl::OBBd> {
 public:
  BoxQuery(const Vector3d& half, const fcl::Transform3d& X_OB) : box_(OrientedBox(half, X_OB)) {}
  bool Meets(const fcl::OBBd& node) const { return node.overlap(box_); }

 private:
  fcl::OBBd box_;
};

template <>
class BoxQuery<fcl::OBBRSSd> {
 public:
  BoxQuery(const Vector3d& half, const fcl::Transform3d& X_OB) : box_(OrientedBox(half, X_OB)) {}
  bool Meets(const fcl::OBBRSSd& node) const { return node.obb.overlap(box_); }

 private:
  fcl::OBBd box_;
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

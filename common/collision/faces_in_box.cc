#include "common/collision/faces_in_box.h"

#include <cmath>

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

// Whether volumes of kind BV have an oriented culling box (OBB, OBBRSS).
template <typename BV>
constexpr bool kOrientedVolume = requires(const BV& bv) {
  CullingBox(bv);
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
    if constexpr (!kOrientedVolume<BV>) fcl::computeBV(fcl::Boxd(2 * half), X_OB, converted_);
  }
  bool Meets(const BV& node) const {
    if constexpr (kOrientedVolume<BV>) {
      const fcl::OBBd& volume = CullingBox(node);
      return !BoxesDisjoint(volume, volume.extent.norm(), box_);
    } else {
      return node.overlap(converted_);
    }
  }
  /// Whether `node`'s volume lies wholly inside the box: every face below
  /// it meets the box. Only oriented volumes tell; the others never do.
  bool Holds(const BV& node) const {
    if constexpr (kOrientedVolume<BV>) {
      const fcl::OBBd& volume = CullingBox(node);
      const Vector3d offset = volume.To - box_.center;
      for (int i = 0; i < 3; ++i) {
        const Vector3d axis = box_.axis.col(i);
        double reach = std::abs(axis.dot(offset));
        for (int j = 0; j < 3; ++j)
          reach += volume.extent[j] * std::abs(axis.dot(volume.axis.col(j)));
        if (reach > box_.extent[i]) return false;
      }
      return true;
    } else {
      return false;
    }
  }

 private:
  PlacedBox box_;
  BV converted_;
};

template <typename BV>
void FindFacesInBox(const fcl::BVHModel<BV>& bvh, const CollisionModel::Impl& impl,
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
      if (!impl.degenerate[node.primitiveId()]) faces.push_back(node.primitiveId());
    } else if (query.Holds(node.bv)) {
      // Every leaf below, in the walk's order, without a test each: most
      // of a large box's faces lie well inside it.
      const int end = node.first_primitive + node.num_primitives;
      for (int i = node.first_primitive; i < end; ++i) {
        const int face = impl.leaf_faces[i];
        if (!impl.degenerate[face]) faces.push_back(face);
      }
    } else {
      stack.push_back(node.rightChild());
      stack.push_back(node.leftChild());
    }
  }
}

// AnyCornerInFront down one hierarchy, the plane (n_O, offset) in the
// object frame: a point x is in front by n_O . x - offset. Of a node's
// children the one reaching farther in front is opened first: a plane
// with the surface in front of it is told so after a short walk.
template <typename BV>
bool AnyCornerInFront(const fcl::BVHModel<BV>& bvh, const Isometry3d& X_OW,
                      const AlignedBox3d& box_W, const Vector3d& n_O, double offset) {
  fcl::Transform3d X_OB = X_OW;
  X_OB.translation() = X_OW * box_W.center();
  const BoxQuery<BV> query(box_W.sizes() / 2, X_OB);
  // How far node i's volume reaches in front of the plane (> 0: it may
  // hold a corner in front; every volume but an oriented one may).
  auto in_front = [&](int i) {
    const fcl::BVNode<BV>& node = bvh.getBV(i);
    if constexpr (kOrientedVolume<BV>) {
      const fcl::OBBd& volume = CullingBox(node.bv);
      return n_O.dot(volume.To) - offset +
             volume.extent[0] * std::abs(n_O.dot(volume.axis.col(0))) +
             volume.extent[1] * std::abs(n_O.dot(volume.axis.col(1))) +
             volume.extent[2] * std::abs(n_O.dot(volume.axis.col(2)));
    } else {
      return 1.0;
    }
  };
  // An oriented volume is opened when its bounding sphere meets the box
  // (a fifth of the full test's work, and these walks open most volumes
  // they meet); the other kinds by the box query.
  const Matrix3d R_BO = X_OB.linear().transpose();
  const Vector3d half = box_W.sizes() / 2;
  auto open = [&](int i) {
    const BV& bv = bvh.getBV(i).bv;
    if constexpr (kOrientedVolume<BV>) {
      const fcl::OBBd& volume = CullingBox(bv);
      const Vector3d c = R_BO * (volume.To - X_OB.translation());
      const double outside = (c.cwiseAbs() - half).cwiseMax(0.0).squaredNorm();
      return outside <= volume.extent.squaredNorm();
    } else {
      return query.Meets(bv);
    }
  };
  std::vector<int>& stack = Scratch<NodeStack>().nodes;
  stack.clear();
  if (in_front(0) > 0 && open(0)) stack.push_back(0);
  while (!stack.empty()) {
    const fcl::BVNode<BV>& node = bvh.getBV(stack.back());
    stack.pop_back();
    if (node.isLeaf()) {
      const fcl::Triangle& t = bvh.tri_indices[node.primitiveId()];
      for (int k = 0; k < 3; ++k) {
        if (n_O.dot(bvh.vertices[t[k]]) > offset) return true;
      }
      continue;
    }
    const int left = node.leftChild(), right = node.rightChild();
    const double left_front = in_front(left), right_front = in_front(right);
    const int first = left_front >= right_front ? left : right;
    const int second = first == left ? right : left;
    const double second_front = first == left ? right_front : left_front;
    if (second_front > 0 && open(second)) stack.push_back(second);
    if (std::max(left_front, right_front) > 0 && open(first)) stack.push_back(first);
  }
  return false;
}

}  // namespace

void FindFacesInBox(const CollisionModel& model, const Isometry3d& X_WO, const AlignedBox3d& box_W,
                    std::vector<FaceId>& faces) {
  const CollisionModel::Impl& impl = model.impl();
  if (box_W.isEmpty()) return;
  std::visit(
      [&](const auto& bvh) {
        if (bvh->getNumBVs() > 0) {
          FindFacesInBox(*bvh, impl, X_WO.inverse(), box_W, faces);
        }
      },
      impl.bvh);
}

bool AnyCornerInFront(const CollisionModel& model, const Isometry3d& X_WO,
                      const AlignedBox3d& box_W, const Vector3d& point_W, const Vector3d& normal_W,
                      double slack_m) {
  if (box_W.isEmpty()) return false;
  const Isometry3d X_OW = X_WO.inverse();
  const Vector3d n_O = X_OW.linear() * normal_W;
  const double offset = n_O.dot(X_OW * point_W) + slack_m;
  // A plane or box that is not a number may have anything in front of it.
  if (!n_O.allFinite() || !std::isfinite(offset) || !box_W.sizes().allFinite()) return true;
  return std::visit(
      [&](const auto& bvh) {
        return bvh->getNumBVs() > 0 && AnyCornerInFront(*bvh, X_OW, box_W, n_O, offset);
      },
      model.impl().bvh);
}

}  // namespace hs

#include "common/collision/triangle_pairs.h"

#include <utility>

#include "common/collision/fcl_bvh.h"
#include "common/core/check.h"

namespace hs {
namespace {

// Overlap of a volume of A (frame A) and a volume of B (frame B), with
// (R, T) mapping frame B into frame A, as FCL's own traversal nodes do.
template <typename BV>
bool Overlap(const Matrix3d& R, const Vector3d& T, const BV& bv_a, const BV& bv_b) {
  return fcl::overlap(R, T, bv_a, bv_b);
}
// FCL has no oriented test for axis-aligned boxes: B's box seen from A is an
// oriented box, so test them as OBBs.
template <>
bool Overlap(const Matrix3d& R, const Vector3d& T, const fcl::AABBd& bv_a, const fcl::AABBd& bv_b) {
  fcl::OBBd a, b;
  a.axis.setIdentity();
  a.To = bv_a.center();
  a.extent = (bv_a.max_ - bv_a.min_) / 2;
  b.axis = R;
  b.To = R * bv_b.center() + T;
  b.extent = (bv_b.max_ - bv_b.min_) / 2;
  return a.overlap(b);
}

// FCL's traversal nodes dispatch every test through virtual calls and, for
// AABB hierarchies, copy both models on each query; this loop walks the
// same FCL hierarchies with the same FCL volume tests, without either cost,
// and with our exact SAT triangle test at the leaves.
template <typename BV>
int64_t Traverse(const fcl::BVHModel<BV>& ma, const CollisionModel::Impl& ia,
                 const fcl::BVHModel<BV>& mb, const CollisionModel::Impl& ib,
                 const Isometry3d& X_AB, double margin, std::vector<TrianglePair>& pairs) {
  const Matrix3d R = X_AB.linear();
  const Vector3d T = X_AB.translation();
  int64_t tests = 0;
  // Reused across calls so that a steady stream of queries does not allocate.
  thread_local std::vector<std::pair<int, int>> stack;
  stack.clear();
  stack.emplace_back(0, 0);
  while (!stack.empty()) {
    const auto [i, j] = stack.back();
    stack.pop_back();
    const fcl::BVNode<BV>& na = ma.getBV(i);
    const fcl::BVNode<BV>& nb = mb.getBV(j);
    ++tests;
    if (!Overlap(R, T, na.bv, nb.bv)) continue;
    const bool leaf_a = na.isLeaf(), leaf_b = nb.isLeaf();
    if (leaf_a && leaf_b) {
      const int fa = na.primitiveId(), fb = nb.primitiveId();
      if (ia.degenerate[fa] || ib.degenerate[fb]) continue;
      Triangle3d tb = ib.triangle(fb);
      for (Vector3d& p : tb) p = X_AB * p;
      if (TrianglesIntersect(ia.triangle(fa), tb, margin)) pairs.push_back({fa, fb});
      continue;
    }
    if (leaf_b || (!leaf_a && na.bv.size() >= nb.bv.size())) {
      stack.emplace_back(na.leftChild(), j);
      stack.emplace_back(na.rightChild(), j);
    } else {
      stack.emplace_back(i, nb.leftChild());
      stack.emplace_back(i, nb.rightChild());
    }
  }
  return tests;
}

}  // namespace

int64_t FindIntersectingTriangles(const CollisionModel& a, const Isometry3d& X_WA,
                                  const CollisionModel& b, const Isometry3d& X_WB, double margin_m,
                                  std::vector<TrianglePair>& pairs) {
  HS_CHECK(a.bv_type() == b.bv_type());
  HS_CHECK(margin_m <= a.margin_m() + b.margin_m());
  const Isometry3d X_AB = X_WA.inverse() * X_WB;
  const CollisionModel::Impl& ia = a.impl();
  const CollisionModel::Impl& ib = b.impl();
  return std::visit(
      [&](const auto& ma) -> int64_t {
        using Model = typename std::decay_t<decltype(ma)>::element_type;
        const auto& mb = std::get<std::shared_ptr<Model>>(ib.bvh);
        return Traverse(*ma, ia, *mb, ib, X_AB, margin_m, pairs);
      },
      ia.bvh);
}

}  // namespace hs

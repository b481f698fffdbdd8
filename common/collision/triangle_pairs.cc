#include "common/collision/triangle_pairs.h"

#include <utility>

#include "common/collision/fcl_bvh.h"
#include "common/collision/obb_overlap.h"
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

// A volume holding everything `bv` sweeps through when moved by -v for a
// parameter in [0, 1]: moved by -v/2 and grown by half of v (exactly along
// box axes, by |v|/2 for spheres and swept rectangles).
fcl::OBBd Swept(const fcl::OBBd& bv, const Vector3d& v) {
  fcl::OBBd out = bv;
  out.To -= v / 2;
  out.extent += (bv.axis.transpose() * v).cwiseAbs() / 2;
  return out;
}
fcl::RSSd Swept(const fcl::RSSd& bv, const Vector3d& v) {
  fcl::RSSd out = bv;
  out.To -= v / 2;
  out.r += v.norm() / 2;
  return out;
}
fcl::OBBRSSd Swept(const fcl::OBBRSSd& bv, const Vector3d& v) {
  fcl::OBBRSSd out;
  out.obb = Swept(bv.obb, v);
  out.rss = Swept(bv.rss, v);
  return out;
}
fcl::kIOSd Swept(const fcl::kIOSd& bv, const Vector3d& v) {
  fcl::kIOSd out = bv;
  for (unsigned i = 0; i < out.num_spheres; ++i) {
    out.spheres[i].o -= v / 2;
    out.spheres[i].r += v.norm() / 2;
  }
  out.obb = Swept(bv.obb, v);
  return out;
}
fcl::AABBd Swept(const fcl::AABBd& bv, const Vector3d& v) {
  fcl::AABBd out = bv;
  out.min_ = bv.min_.cwiseMin(bv.min_ - v);
  out.max_ = bv.max_.cwiseMax(bv.max_ - v);
  return out;
}

// The box that carries each volume's culling test, for the fast path.
const fcl::OBBd& CullingBox(const fcl::OBBd& bv) { return bv; }
const fcl::OBBd& CullingBox(const fcl::OBBRSSd& bv) { return bv.obb; }

// The volume test of one traversal: oriented boxes (OBB, OBBRSS) take the
// lean cached path, the other volumes FCL's own tests.
template <typename BV>
class VolumeTest {
 public:
  VolumeTest(const fcl::BVHModel<BV>& mb, const Matrix3d& R, const Vector3d& T,
             const Vector3d* sweep_A)
      : R_(R), T_(T), sweep_A_(sweep_A) {
    if (kFast && !sweep_A) cache().Start(mb.getNumBVs(), R, T);
  }

  bool Overlap(const BV& a, int j, const BV& b) const {
    if (sweep_A_) return hs::Overlap(R_, T_, Swept(a, *sweep_A_), b);
    if constexpr (kFast) {
      const fcl::OBBd& box_a = CullingBox(a);
      return !BoxesDisjoint(box_a, box_a.extent.norm(), cache().Get(j, CullingBox(b)));
    } else {
      return hs::Overlap(R_, T_, a, b);
    }
  }

 private:
  static constexpr bool kFast = std::is_same_v<BV, fcl::OBBd> || std::is_same_v<BV, fcl::OBBRSSd>;
  static PlacedBoxCache& cache() {
    thread_local PlacedBoxCache c;
    return c;
  }

  const Matrix3d R_;
  const Vector3d T_;
  const Vector3d* sweep_A_;
};

// FCL's traversal nodes dispatch every test through virtual calls and, for
// AABB hierarchies, copy both models on each query; this loop walks the
// same FCL hierarchies with the same FCL volume tests, without either cost,
// and with our exact SAT triangle test at the leaves. With a `sweep_A`
// (A's motion in A's frame), A's volumes are swept along it and the leaf
// test asks whether the sweep interval meets the motion.
template <typename BV>
int64_t Traverse(const fcl::BVHModel<BV>& ma, const CollisionModel::Impl& ia,
                 const fcl::BVHModel<BV>& mb, const CollisionModel::Impl& ib,
                 const Isometry3d& X_AB, const Vector3d* sweep_A, double margin,
                 std::vector<TrianglePair>& pairs) {
  const Matrix3d R = X_AB.linear();
  const Vector3d T = X_AB.translation();
  const VolumeTest<BV> volumes(mb, R, T, sweep_A);
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
    if (!volumes.Overlap(na.bv, j, nb.bv)) continue;
    const bool leaf_a = na.isLeaf(), leaf_b = nb.isLeaf();
    if (leaf_a && leaf_b) {
      const int fa = na.primitiveId(), fb = nb.primitiveId();
      if (ia.degenerate[fa] || ib.degenerate[fb]) continue;
      Triangle3d tb = ib.triangle(fb);
      for (Vector3d& p : tb) p = X_AB * p;
      const Triangle3d ta = ia.triangle(fa);
      const bool hit = sweep_A ? SweptIntersection(ta, tb, *sweep_A, margin).Overlaps(0, 1)
                               : TrianglesIntersect(ta, tb, margin);
      if (hit) pairs.push_back({fa, fb});
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

int64_t Find(const CollisionModel& a, const Isometry3d& X_WA, const Vector3d* sweep_W,
             const CollisionModel& b, const Isometry3d& X_WB, double margin_m,
             std::vector<TrianglePair>& pairs) {
  HS_CHECK(a.bv_type() == b.bv_type());
  HS_CHECK(margin_m <= a.margin_m() + b.margin_m());
  const Isometry3d X_AB = X_WA.inverse() * X_WB;
  const Vector3d sweep_A = sweep_W ? Vector3d(X_WA.linear().transpose() * *sweep_W) : Vector3d();
  const CollisionModel::Impl& ia = a.impl();
  const CollisionModel::Impl& ib = b.impl();
  return std::visit(
      [&](const auto& ma) -> int64_t {
        using Model = typename std::decay_t<decltype(ma)>::element_type;
        const auto& mb = std::get<std::shared_ptr<Model>>(ib.bvh);
        return Traverse(*ma, ia, *mb, ib, X_AB, sweep_W ? &sweep_A : nullptr, margin_m, pairs);
      },
      ia.bvh);
}

}  // namespace

int64_t FindIntersectingTriangles(const CollisionModel& a, const Isometry3d& X_WA,
                                  const CollisionModel& b, const Isometry3d& X_WB, double margin_m,
                                  std::vector<TrianglePair>& pairs) {
  return Find(a, X_WA, nullptr, b, X_WB, margin_m, pairs);
}

int64_t FindSweptTrianglePairs(const CollisionModel& a, const Isometry3d& X_WA,
                               const Vector3d& sweep_W, const CollisionModel& b,
                               const Isometry3d& X_WB, double margin_m,
                               std::vector<TrianglePair>& pairs) {
  return Find(a, X_WA, &sweep_W, b, X_WB, margin_m, pairs);
}

}  // namespace hs

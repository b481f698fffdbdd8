#include "common/collision/triangle_pairs.h"

#include <algorithm>
#include <array>
#include <bit>
#include <limits>
#include <numeric>
#include <utility>

#include "common/collision/fcl_bvh.h"
#include "common/collision/obb_overlap.h"
#include "common/collision/placed_faces.h"
#include "common/core/check.h"
#include "common/core/scratch.h"

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

// The volume test of one traversal: oriented boxes (OBB, OBBRSS) take the
// lean cached path, the other volumes FCL's own tests.
template <typename BV>
class VolumeTest {
 public:
  VolumeTest(const fcl::BVHModel<BV>& mb, const Matrix3d& R, const Vector3d& T,
             const Vector3d* sweep_A)
      : R_(R), T_(T), sweep_A_(sweep_A) {
    if (kFast) cache().Start(mb.getNumBVs(), R, T);
  }

  bool Overlap(const BV& a, int j, const BV& b) const {
    if constexpr (kFast) {
      // A swept box is a box: the lean test serves both queries.
      const fcl::OBBd box_a = sweep_A_ ? Swept(CullingBox(a), *sweep_A_) : CullingBox(a);
      return !BoxesDisjoint(box_a, box_a.extent.norm(), cache().Get(j, CullingBox(b)));
    } else {
      return hs::Overlap(R_, T_, sweep_A_ ? Swept(a, *sweep_A_) : a, b);
    }
  }

 private:
  static constexpr bool kFast = std::is_same_v<BV, fcl::OBBd> || std::is_same_v<BV, fcl::OBBRSSd>;
  struct Cache {  // one per volume type
    PlacedBoxCache boxes;
  };
  static PlacedBoxCache& cache() { return Scratch<Cache>().boxes; }

  const Matrix3d R_;
  const Vector3d T_;
  const Vector3d* sweep_A_;
};

// Nodes holding at most this many faces each are not split further: both
// buckets are cut down to the faces whose boxes (in A's frame) meet the
// overlap of the buckets' boxes, and those pairs go through a box test that
// costs a tenth of an oriented-box test, then SAT. The last levels of the
// hierarchies cost more volume tests than the face pairs they cull. Instructions
// per query (callgrind, contact_bench cases #1-#4) at 1 (a plain leaf walk)
// -> 32: 149k -> 125k, 324k -> 282k, 2.53M -> 2.45M, 11.0M -> 7.7M; 8, 16
// and 64 were each worse on some case. With the bit-mask box tests, 16
// still costs more than 32 (whole contact query, #3: 3.49M against 2.98M;
// #4: 12.3M against 11.7M).
constexpr int kBucketFaces = 32;

// What a query asks, beside the models and their poses.
struct Query {
  const Vector3d* sweep_W;  // A's motion (world frame), or none for a static query
  double margin_m;
  bool first_only;  // stop at the first pair found
  SweptFaceTest face_test;
  std::span<const TrianglePair> skip;
};

// The faces of B placed in A's frame, kept from query to query.
struct PlacedFacesOfB {
  PlacedFaces faces;
};
// Where each face of A starts in a query's `skip`.
struct SkipStarts {
  std::vector<int> begin;
};

// The faces of both objects in A's frame, for the leaf buckets.
class BucketTest {
 public:
  template <typename BV>
  BucketTest(const CollisionModel::Impl& ia, const fcl::BVHModel<BV>& mb,
             const CollisionModel::Impl& ib, const Isometry3d& X_AB, const Vector3d* sweep_A,
             const Query& query)
      : ia_(ia),
        ib_(ib),
        sweep_A_(sweep_A),
        margin_(query.margin_m),
        planes_only_(query.face_test == SweptFaceTest::kPlanesOnly),
        skip_(query.skip),
        faces_b_(Scratch<PlacedFacesOfB>().faces),
        skip_begin_(Scratch<SkipStarts>().begin),
        buffers_(Scratch<RunBuffers>()) {
    faces_b_.Start(mb.vertices, mb.tri_indices, mb.num_tris, X_AB);
    if (!skip_.empty()) {  // where each face of A starts in `skip`, sorted by A's face
      std::vector<int>& begin = skip_begin_;
      begin.assign(ia.leaf_faces.size() + 1, 0);
      for (const TrianglePair& p : skip_) ++begin[p.a + 1];
      std::partial_sum(begin.begin(), begin.end(), begin.begin());
    }
  }

  /// Tests every face of A's node `na` against every face of B's node `nb`:
  /// first each bucket is cut down to the faces whose boxes meet the overlap
  /// of the two buckets' boxes, then the rest go through box and SAT tests.
  /// A's faces are read in leaf order, their boxes from the model's arrays
  /// (swept: grown by the sweep, which moves every face alike).
  template <typename Node>
  void Run(const Node& na, const Node& nb, std::vector<TrianglePair>& pairs) const {
    std::vector<Entry>& list_b = buffers_.list_b;
    Vector3d lo_b, hi_b;
    StartList(list_b, lo_b, hi_b);
    for (int i = nb.first_primitive; i < nb.first_primitive + nb.num_primitives; ++i) {
      const int f = ib_.leaf_faces[i];
      if (!ib_.degenerate[f]) AddEntry(f, &faces_b_.Get(f), list_b, lo_b, hi_b);
    }
    const int first = na.first_primitive, count = na.num_primitives;
    double grow_lo[3] = {0, 0, 0}, grow_hi[3] = {0, 0, 0};
    if (sweep_A_) {
      for (int d = 0; d < 3; ++d) {
        grow_lo[d] = std::min(0.0, -(*sweep_A_)[d]);
        grow_hi[d] = std::max(0.0, -(*sweep_A_)[d]);
      }
    }
    double lo[3], hi[3];  // the overlap of the two buckets' boxes, grown by the margin
    for (int d = 0; d < 3; ++d) {
      const double* a_lo = ia_.leaf_order_lo[d].data() + first;
      const double* a_hi = ia_.leaf_order_hi[d].data() + first;
      double lo_a = std::numeric_limits<double>::infinity(), hi_a = -lo_a;
      for (int k = 0; k < count; ++k) {
        lo_a = std::min(lo_a, a_lo[k]);
        hi_a = std::max(hi_a, a_hi[k]);
      }
      lo[d] = std::max(lo_a + grow_lo[d], lo_b[d]) - margin_;
      hi[d] = std::min(hi_a + grow_hi[d], hi_b[d]) + margin_;
      if (lo[d] > hi[d]) return;
    }
    uint32_t faces_a = count == 32 ? ~uint32_t{0} : (uint32_t{1} << count) - 1;
    for (int d = 0; d < 3; ++d) {
      const double* a_lo = ia_.leaf_order_lo[d].data() + first;
      const double* a_hi = ia_.leaf_order_hi[d].data() + first;
      uint32_t meets = 0;
      for (int k = 0; k < count; ++k) {
        const bool meet = (a_lo[k] + grow_lo[d] <= hi[d]) & (lo[d] <= a_hi[k] + grow_hi[d]);
        meets |= uint32_t{meet} << k;
      }
      faces_a &= meets;
    }
    Crop(list_b, lo, hi);
    BucketBoxes& boxes_b = buffers_.boxes_b;
    boxes_b.Set(list_b, margin_);
    for (; faces_a != 0; faces_a &= faces_a - 1) {
      const int i = first + std::countr_zero(faces_a);
      const int a = ia_.leaf_faces[i];
      const PlacedFace& face_a = ia_.leaf_order_faces[i];
      double box_lo[3], box_hi[3];
      for (int d = 0; d < 3; ++d) {
        box_lo[d] = ia_.leaf_order_lo[d][i] + grow_lo[d];
        box_hi[d] = ia_.leaf_order_hi[d][i] + grow_hi[d];
      }
      const std::span<const TrianglePair> skipped = Skipped(a);
      for (uint32_t meets = boxes_b.Meeting(box_lo, box_hi, margin_); meets != 0;
           meets &= meets - 1) {
        const Entry& b = list_b[std::countr_zero(meets)];
        if (!skipped.empty() && std::ranges::binary_search(skipped, TrianglePair{a, b.id})) {
          continue;
        }
        const bool hit = sweep_A_ ? SweptFacesMeet(face_a, *b.face)
                                  : TrianglesIntersect(face_a.triangle, face_a.normal,
                                                       b.face->triangle, b.face->normal, margin_);
        if (hit) pairs.push_back({a, b.id});
      }
    }
  }

 private:
  struct Entry {
    int id;
    const PlacedFace* face;
  };

  // A cut-down bucket's face boxes, coordinate by coordinate, for a scan
  // without branches: which of them meet a box within the margin is one
  // bit mask.
  struct BucketBoxes {
    std::array<double, kBucketFaces> lo[3], hi_plus_margin[3];
    int size = 0;

    void Set(const std::vector<Entry>& list, double margin) {
      size = static_cast<int>(list.size());
      for (int k = 0; k < size; ++k) {
        for (int d = 0; d < 3; ++d) {
          lo[d][k] = list[k].face->lo[d];
          hi_plus_margin[d][k] = list[k].face->hi[d] + margin;
        }
      }
    }

    // Bit k: whether entry k's box meets the box [lo, hi] within the margin.
    uint32_t Meeting(const double (&box_lo)[3], const double (&box_hi)[3], double margin) const {
      const double hi_plus[3] = {box_hi[0] + margin, box_hi[1] + margin, box_hi[2] + margin};
      uint32_t meets = 0;
      for (int k = 0; k < size; ++k) {
        const bool meet = (box_lo[0] <= hi_plus_margin[0][k]) & (lo[0][k] <= hi_plus[0]) &
                          (box_lo[1] <= hi_plus_margin[1][k]) & (lo[1][k] <= hi_plus[1]) &
                          (box_lo[2] <= hi_plus_margin[2][k]) & (lo[2][k] <= hi_plus[2]);
        meets |= uint32_t{meet} << k;
      }
      return meets;
    }
  };
  static_assert(kBucketFaces <= 32, "one bit per face of a bucket");

  // Run's lists, kept from bucket to bucket.
  struct RunBuffers {
    std::vector<Entry> list_b;
    BucketBoxes boxes_b;
  };

  // Whether face a, moved by -t sweep for some t in [0, 1], meets face b.
  // The plane tests first: SweptIntersection builds every axis before its
  // first, and most pairs whose boxes meet stay on one side of a plane all
  // along the sweep. A moves by -t sweep, so B moves off A's plane by
  // +t (n_a . sweep), and A off B's plane by -t (n_b . sweep).
  bool SweptFacesMeet(const PlacedFace& a, const PlacedFace& b) const {
    if (BeyondFacePlane(a, b.triangle, margin_, a.normal.dot(*sweep_A_)) ||
        BeyondFacePlane(b, a.triangle, margin_, -b.normal.dot(*sweep_A_))) {
      return false;
    }
    if (planes_only_) {
      return SweptPlanesMeet(a.triangle, a.normal, b.triangle, b.normal, *sweep_A_, margin_,
                             {0, 1});
    }
    return !SweptIntersection(a.triangle, a.normal, b.triangle, b.normal, *sweep_A_, margin_,
                              {0, 1})
                .empty();
  }

  // The pairs of `skip_` with A's face `a`.
  std::span<const TrianglePair> Skipped(int a) const {
    if (skip_.empty()) return {};
    const std::vector<int>& begin = skip_begin_;
    return skip_.subspan(begin[a], begin[a + 1] - begin[a]);
  }

  static void StartList(std::vector<Entry>& list, Vector3d& lo, Vector3d& hi) {
    list.clear();
    lo.setConstant(std::numeric_limits<double>::infinity());
    hi = -lo;
  }

  // Adds a face to a bucket's list and its box to the bucket's box.
  static void AddEntry(int id, const PlacedFace* face, std::vector<Entry>& list, Vector3d& lo,
                       Vector3d& hi) {
    list.push_back({id, face});
    lo = lo.cwiseMin(face->lo);
    hi = hi.cwiseMax(face->hi);
  }

  // Keeps the entries whose boxes meet the box [lo, hi], without a branch
  // per entry: which ones go is as good as random.
  static void Crop(std::vector<Entry>& list, const double (&lo)[3], const double (&hi)[3]) {
    size_t kept = 0;
    for (const Entry& e : list) {
      const PlacedFace& f = *e.face;
      list[kept] = e;
      kept += (f.lo[0] <= hi[0]) & (lo[0] <= f.hi[0]) &  //
              (f.lo[1] <= hi[1]) & (lo[1] <= f.hi[1]) &  //
              (f.lo[2] <= hi[2]) & (lo[2] <= f.hi[2]);
    }
    list.resize(kept);
  }

  const CollisionModel::Impl& ia_;
  const CollisionModel::Impl& ib_;
  const Vector3d* sweep_A_;
  const double margin_;
  const bool planes_only_;
  const std::span<const TrianglePair> skip_;
  PlacedFaces& faces_b_;
  std::vector<int>& skip_begin_;
  RunBuffers& buffers_;
};

// FCL's traversal nodes dispatch every test through virtual calls and, for
// AABB hierarchies, copy both models on each query; this loop walks the
// same FCL hierarchies with the same FCL volume tests, without either cost,
// and with buckets of faces under our exact SAT triangle test at the
// bottom. With a `sweep_A` (A's motion in A's frame), A's volumes are swept
// along it and the face test asks whether the sweep interval meets the
// motion.
// The node pairs a traversal has still to visit.
struct TraversalStack {
  std::vector<std::pair<int, int>> pairs;
};

template <typename BV>
int64_t Traverse(const fcl::BVHModel<BV>& ma, const CollisionModel::Impl& ia,
                 const fcl::BVHModel<BV>& mb, const CollisionModel::Impl& ib,
                 const Isometry3d& X_AB, const Vector3d* sweep_A, const Query& query,
                 std::vector<TrianglePair>& pairs) {
  const Matrix3d R = X_AB.linear();
  const Vector3d T = X_AB.translation();
  const VolumeTest<BV> volumes(mb, R, T, sweep_A);
  const BucketTest buckets(ia, mb, ib, X_AB, sweep_A, query);
  int64_t tests = 0;
  const size_t pairs_before = pairs.size();
  // Kept across calls so that a steady stream of queries does not allocate.
  std::vector<std::pair<int, int>>& stack = Scratch<TraversalStack>().pairs;
  stack.clear();
  stack.emplace_back(0, 0);
  while (!stack.empty()) {
    const auto [i, j] = stack.back();
    stack.pop_back();
    const fcl::BVNode<BV>& na = ma.getBV(i);
    const fcl::BVNode<BV>& nb = mb.getBV(j);
    ++tests;
    if (!volumes.Overlap(na.bv, j, nb.bv)) continue;
    const bool small_a = na.num_primitives <= kBucketFaces;
    const bool small_b = nb.num_primitives <= kBucketFaces;
    if (small_a && small_b) {
      buckets.Run(na, nb, pairs);
      if (query.first_only && pairs.size() > pairs_before) break;
    } else if (small_b || (!small_a && na.bv.size() >= nb.bv.size())) {
      stack.emplace_back(na.leftChild(), j);
      stack.emplace_back(na.rightChild(), j);
    } else {
      stack.emplace_back(i, nb.leftChild());
      stack.emplace_back(i, nb.rightChild());
    }
  }
  return tests;
}

// A query's `skip` with its pairs turned round.
struct SkipTurnedRound {
  std::vector<TrianglePair> pairs;
};

int64_t Find(const CollisionModel& a, const Isometry3d& X_WA, const CollisionModel& b,
             const Isometry3d& X_WB, const Query& query, std::vector<TrianglePair>& pairs) {
  HS_CHECK(a.bv_type() == b.bv_type());
  HS_CHECK(query.margin_m <= a.margin_m() + b.margin_m());
  // The traversal works in its first object's frame, whose faces come ready
  // placed (leaf_order_faces), and maps the other's into it: let the larger
  // mesh go first. A moved by -t sweep meets B where B moved by +t sweep
  // meets A, so the sweep turns round, and so do the pairs found.
  if (b.impl().leaf_faces.size() > a.impl().leaf_faces.size()) {
    const Vector3d sweep_back = query.sweep_W ? Vector3d(-*query.sweep_W) : Vector3d();
    // Once turned round, A is the larger: no second turn reuses this.
    std::vector<TrianglePair>& skip_back = Scratch<SkipTurnedRound>().pairs;
    skip_back.clear();
    for (const TrianglePair& p : query.skip) skip_back.push_back({p.b, p.a});
    std::ranges::sort(skip_back);
    Query back = query;
    back.sweep_W = query.sweep_W ? &sweep_back : nullptr;
    back.skip = skip_back;
    const size_t first = pairs.size();
    const int64_t tests = Find(b, X_WB, a, X_WA, back, pairs);
    for (size_t i = first; i < pairs.size(); ++i) std::swap(pairs[i].a, pairs[i].b);
    return tests;
  }
  const Isometry3d X_AB = X_WA.inverse() * X_WB;
  const Vector3d sweep_A =
      query.sweep_W ? Vector3d(X_WA.linear().transpose() * *query.sweep_W) : Vector3d();
  const CollisionModel::Impl& ia = a.impl();
  const CollisionModel::Impl& ib = b.impl();
  return std::visit(
      [&](const auto& ma) -> int64_t {
        using Model = typename std::decay_t<decltype(ma)>::element_type;
        const auto& mb = std::get<std::shared_ptr<Model>>(ib.bvh);
        return Traverse(*ma, ia, *mb, ib, X_AB, query.sweep_W ? &sweep_A : nullptr, query, pairs);
      },
      ia.bvh);
}

}  // namespace

int64_t FindIntersectingTriangles(const CollisionModel& a, const Isometry3d& X_WA,
                                  const CollisionModel& b, const Isometry3d& X_WB, double margin_m,
                                  std::vector<TrianglePair>& pairs,
                                  std::span<const TrianglePair> skip) {
  return Find(a, X_WA, b, X_WB,
              {.sweep_W = nullptr,
               .margin_m = margin_m,
               .first_only = false,
               .face_test = SweptFaceTest::kEveryAxis,
               .skip = skip},
              pairs);
}

int64_t FindSweptTrianglePairs(const CollisionModel& a, const Isometry3d& X_WA,
                               const Vector3d& sweep_W, const CollisionModel& b,
                               const Isometry3d& X_WB, double margin_m,
                               std::vector<TrianglePair>& pairs, std::span<const TrianglePair> skip,
                               SweptFaceTest face_test) {
  return Find(a, X_WA, b, X_WB,
              {.sweep_W = &sweep_W,
               .margin_m = margin_m,
               .first_only = false,
               .face_test = face_test,
               .skip = skip},
              pairs);
}

namespace {
// Where AnyTrianglesMeet's query puts the pair it stops at.
struct FirstPair {
  std::vector<TrianglePair> pairs;
};
}  // namespace

bool AnyTrianglesMeet(const CollisionModel& a, const Isometry3d& X_WA,
                      const std::optional<Vector3d>& sweep_W, const CollisionModel& b,
                      const Isometry3d& X_WB, double margin_m) {
  std::vector<TrianglePair>& pairs = Scratch<FirstPair>().pairs;
  pairs.clear();
  Find(a, X_WA, b, X_WB,
       {.sweep_W = sweep_W ? &*sweep_W : nullptr,
        .margin_m = margin_m,
        .first_only = true,
        .face_test = SweptFaceTest::kEveryAxis,
        .skip = {}},
       pairs);
  return !pairs.empty();
}

}  // namespace hs

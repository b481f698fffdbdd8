#include "common/collision/triangle_pairs.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <limits>
#include <utility>

#include "common/collision/bucket_boxes.h"
#include "common/collision/face_test_batch.h"
#include "common/collision/fcl_bvh.h"
#include "common/collision/obb_overlap.h"
#include "common/collision/placed_faces.h"
#include "common/core/check.h"
#include "common/core/id_memo.h"
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
  // A's volumes are swept along `sweep_A` when given, and grown by
  // `grow_m`.
  VolumeTest(const fcl::BVHModel<BV>& mb, const Matrix3d& R, const Vector3d& T,
             const Vector3d* sweep_A, double grow_m)
      : R_(R), T_(T), sweep_A_(sweep_A), grow_(grow_m) {
    if (kFast) cache().Start(mb.getNumBVs(), R, T);
  }

  bool Overlap(const BV& a, int j, const BV& b) const {
    if constexpr (kFast) {
      // A swept or grown box is a box: the lean test serves every query.
      fcl::OBBd box_a = sweep_A_ ? Swept(CullingBox(a), *sweep_A_) : CullingBox(a);
      if (grow_ > 0) GrowVolume(box_a, grow_);
      return !BoxesDisjoint(box_a, box_a.extent.norm(), cache().Get(j, CullingBox(b)));
    } else {
      BV volume_a = sweep_A_ ? Swept(a, *sweep_A_) : a;
      if (grow_ > 0) GrowVolume(volume_a, grow_);
      return hs::Overlap(R_, T_, volume_a, b);
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
  const double grow_;
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
  // A static query answered from, or building, a region of this cache.
  PairCache* cache = nullptr;
  // Building a region: A's volumes grown by this much (the region's slack,
  // also in margin_m), and every pair whose boxes meet and that neither
  // face's plane keeps beyond margin_m goes here, face tests left out.
  double grow_volumes_m = 0;
  std::vector<PairCache::Candidate>* candidates = nullptr;
};

// The faces of B placed in A's frame, kept from query to query.
struct PlacedFacesOfB {
  PlacedFaces faces;
};
// Each face of A's run of pairs in a query's `skip` (sorted by A's face):
// [begin, end) there. Stamped per query, so a short `skip` costs no pass
// over every face of A.
struct SkipRun {
  int begin = 0, end = 0;
};
struct SkipRuns {
  IdMemo<SkipRun> runs;
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
        candidates_(query.candidates),
        faces_b_(Scratch<PlacedFacesOfB>().faces),
        skip_runs_(Scratch<SkipRuns>().runs),
        buffers_(Scratch<RunBuffers>()) {
    if (sweep_A) {
      for (int d = 0; d < 3; ++d) {
        grow_lo_[d] = std::min(0.0, -(*sweep_A)[d]);
        grow_hi_[d] = std::max(0.0, -(*sweep_A)[d]);
      }
    }
    faces_b_.Start(mb.vertices, mb.num_vertices, mb.tri_indices, mb.num_tris, X_AB);
    if (!skip_.empty()) {
      skip_runs_.Reset(ia.leaf_faces.size());
      for (int k = 0, n = static_cast<int>(skip_.size()); k < n;) {
        const int a = skip_[k].a, begin = k;
        while (k < n && skip_[k].a == a) ++k;
        skip_runs_.Get(a, [&] { return SkipRun{begin, k}; });
      }
    }
  }

  /// Tests every face of A's node `na` (number `node_a` in A's hierarchy)
  /// against every face of B's node `nb`: first each bucket is cut down to
  /// the faces whose boxes meet the other bucket's box (B's first; A's
  /// from node_face_box), then the rest go through box tests
  /// (bucket_boxes.h: B's boxes against each of A's at once), and
  /// those that pass through the face test: at once when swept, left
  /// pending for TestPending when static (a region's build keeps them as
  /// candidates). A's faces are read in leaf order, their boxes from the
  /// model's arrays (swept: grown by the sweep, which moves every face
  /// alike).
  template <typename Node>
  void Run(int node_a, const Node& na, const Node& nb, std::vector<TrianglePair>& pairs) const {
    const BucketOfB& all_b = PlacedBucketOfB(nb);
    std::vector<Entry>& list_b = buffers_.list_b;
    BucketBoxes& boxes_b = buffers_.boxes_b;
    const int first = na.first_primitive, count = na.num_primitives;
    // Every cut below compares as the face boxes' own test (BucketBoxes::
    // Meeting) does, against a box holding the faces', so rounding never
    // makes a cut stricter than that test: the pairs found are exactly
    // those of that test and the face test, as a cached query finds them.
    const AxisBox bucket_a = SweptNodeFaceBox(node_a);
    // B's faces cut down to those whose boxes meet A's bucket box, and the
    // box of those.
    uint32_t kept_b = 0;
    all_b.boxes.Meeting({&bucket_a, 1}, {&kept_b, 1});
    if (kept_b == 0) return;
    boxes_b.Keep(all_b.boxes, kept_b);
    AxisBox kept_box_b = AxisBox::Empty();
    list_b.clear();
    for (; kept_b != 0; kept_b &= kept_b - 1) {
      const Entry& entry = all_b.entries[std::countr_zero(kept_b)];
      list_b.push_back(entry);
      kept_box_b.Include(entry.face->lo.data(), entry.face->hi.data());
    }
    // A's faces whose boxes meet that box, and the box of each.
    const BoxColumns faces_of_a{
        {ia_.leaf_order_lo[0].data() + first, ia_.leaf_order_lo[1].data() + first,
         ia_.leaf_order_lo[2].data() + first},
        {ia_.leaf_order_hi[0].data() + first, ia_.leaf_order_hi[1].data() + first,
         ia_.leaf_order_hi[2].data() + first}};
    uint32_t faces_a =
        GrownBoxesMeeting(faces_of_a, count, grow_lo_, grow_hi_, kept_box_b, margin_);
    std::array<AxisBox, kBucketFaces> boxes_a;
    std::array<int, kBucketFaces> leaves_a;
    size_t n = 0;
    for (; faces_a != 0; faces_a &= faces_a - 1, ++n) {
      const int i = first + std::countr_zero(faces_a);
      leaves_a[n] = i;
      for (int d = 0; d < 3; ++d) {
        boxes_a[n].lo[d] = ia_.leaf_order_lo[d][i] + grow_lo_[d];
        boxes_a[n].hi[d] = ia_.leaf_order_hi[d][i] + grow_hi_[d];
      }
    }
    std::array<uint32_t, kBucketFaces> meets_b;
    boxes_b.Meeting(std::span(boxes_a).first(n), std::span(meets_b).first(n));
    for (size_t q = 0; q < n; ++q) {
      const int i = leaves_a[q];
      const int a = ia_.leaf_faces[i];
      const PlacedFace& face_a = ia_.leaf_order_faces[i];
      const std::span<const TrianglePair> skipped = Skipped(a);
      for (uint32_t meets = meets_b[q]; meets != 0; meets &= meets - 1) {
        const Entry& b = list_b[std::countr_zero(meets)];
        if (!skipped.empty() && std::ranges::binary_search(skipped, TrianglePair{a, b.id})) {
          continue;
        }
        if (sweep_A_) {
          if (SweptFacesMeet(face_a, *b.face)) pairs.push_back({a, b.id});
        } else {
          buffers_.pending.push_back({i, b.id});
        }
      }
    }
  }

  /// For a B of one bucket (node `nb`, B's root): places its faces and the
  /// box of their boxes, for ApartFromBucketOfB.
  template <typename Node>
  void PlaceOneBucketOfB(const Node& nb) const {
    BucketOfB& all_b = buffers_.all_b;
    PlacedBucketOfB(nb);
    all_b.box = AxisBox::Empty();
    for (const Entry& entry : all_b.entries) {
      all_b.box.Include(entry.face->lo.data(), entry.face->hi.data());
    }
  }

  /// Whether no face of a B of one bucket (PlaceOneBucketOfB) has a box
  /// that meets the box of A's node `node_a`'s faces within the margin:
  /// the box of B's boxes misses it, compared as BucketBoxes::Meeting
  /// compares. Then no bucket of A below that node meets one of them
  /// either (its box lies inside), and Run would find nothing there.
  bool ApartFromBucketOfB(int node_a) const {
    const AxisBox& b = buffers_.all_b.box;
    const AxisBox a = SweptNodeFaceBox(node_a);
    for (int d = 0; d < 3; ++d) {
      if (!(a.lo[d] <= b.hi[d] + margin_) || !(b.lo[d] <= a.hi[d] + margin_)) return true;
    }
    return false;
  }

  /// The face tests a static query's Run calls left pending, in the order
  /// they were left: the quick test of them all in batches
  /// (face_test_batch.h), then the full test of those it leaves; the pairs
  /// that meet go to `pairs` in that order. A region's build keeps those
  /// pairs as candidates instead (KeepCandidates).
  void TestPending(std::vector<TrianglePair>& pairs) const {
    std::vector<TrianglePair>& pending = buffers_.pending;
    if (pending.empty()) return;
    if (candidates_) {
      KeepCandidates();
      return;
    }
    std::vector<QuickTriangleTest>& quick = buffers_.face_tests.quick;
    if (quick.size() < pending.size()) quick.resize(pending.size());
    QuickTrianglesTestBatch(ia_.leaf_order_faces.data(), faces_b_.data(), pending, margin_,
                            /*edge_cross=*/true, std::span(quick).first(pending.size()));
    // Written in place, as RunCandidates writes them.
    size_t found = pairs.size();
    pairs.resize(found + pending.size());
    for (size_t k = 0; k < pending.size(); ++k) {
      const auto [i, b] = pending[k];
      bool meet = quick[k].answer == QuickTriangleTest::Answer::kMeet;
      if (quick[k].answer == QuickTriangleTest::Answer::kUnknown) {
        const PlacedFace& face_a = ia_.leaf_order_faces[i];
        const PlacedFace& face_b = faces_b_.Get(b);
        meet = TrianglesIntersect(face_a.triangle, face_a.normal, face_b.triangle, face_b.normal,
                                  margin_);
      }
      if (meet) pairs[found++] = {ia_.leaf_faces[i], b};
    }
    pairs.resize(found);
    pending.clear();
  }

  /// A static query from a region's candidates: each goes through Run's
  /// tests (`skip`, its box test, the face test) in the candidates' order,
  /// Run's own, save those known apart. The region's runs' travel to the
  /// query (Region::to_query) says how far each pair has moved since it
  /// was last tested, and `rounding` (the region's slack beside its skin)
  /// covers the rounding of what was measured there. The face tests run
  /// in two passes: the quick test of them all in batches
  /// (face_test_batch.h: a face's plane keeps them apart, or they cross
  /// clearly), then the full test of those it leaves.
  void RunCandidates(PairCache::Region& region, double rounding,
                     std::vector<TrianglePair>& pairs) const {
    HS_CHECK(!sweep_A_);
    const std::array<PairCache::Travel, PairCache::kStreams>& to_query = region.to_query;
    const int stream = region.stream;
    const double shifted = to_query[stream].shifted_m, turned = to_query[stream].turned;
    FaceTests& tests = buffers_.face_tests;
    tests.Start(region.candidates.size());
    for (PairCache::Candidate& candidate : region.candidates) {
      // Apart by more than the motion since it was last tested: its box,
      // plane or edge-cross test would reject it again.
      const PairCache::Travel& since = to_query[candidate.stream];
      if (since.shifted_m + candidate.per_turn_m * since.turned < candidate.apart_until) continue;
      const int i = candidate.leaf_a;
      const int a = ia_.leaf_faces[i];
      // `skip` before the box test: the pairs a query skips are mostly
      // those the last one found (the exact method's query where M backs
      // out skips those met at the pose), whose boxes meet. A pair skipped
      // keeps what it was known by.
      const std::span<const TrianglePair> skipped = Skipped(a);
      if (!skipped.empty() &&
          std::ranges::binary_search(skipped, TrianglePair{a, candidate.face_b})) {
        continue;
      }
      const PlacedFace& b = faces_b_.Get(candidate.face_b);
      double box_gap = -std::numeric_limits<double>::infinity();
      for (int d = 0; d < 3; ++d) {
        box_gap = std::max(box_gap, std::max(ia_.leaf_order_lo[d][i] - (b.hi[d] + margin_),
                                             b.lo[d] - (ia_.leaf_order_hi[d][i] + margin_)));
      }
      if (box_gap > 0) {  // BucketBoxes::Meeting rejects the pair
        candidate.stream = stream;
        candidate.per_turn_m = Reach(a, candidate.face_b);
        candidate.apart_until = shifted + candidate.per_turn_m * turned + box_gap - rounding;
        continue;
      }
      tests.Add(candidate);
    }
    tests.RunQuickTests(ia_.leaf_order_faces.data(), faces_b_.data(), margin_);
    // The pairs that meet, written in place: a push_back per pair was a
    // call (GCC keeps std::vector's out of line here).
    size_t found = pairs.size();
    pairs.resize(found + tests.size);
    for (size_t k = 0; k < tests.size; ++k) {
      PairCache::Candidate& candidate = *tests.candidates[k];
      const int a = ia_.leaf_faces[candidate.leaf_a];
      // A hint that holds: the quick test's, that of an edge cross that
      // keeps the pair apart (the one kept from its last test, or the
      // facing edges' cross the second quick test found), or the full
      // test's own.
      PairHint hint{.edge_pair = candidate.edge_pair, .gap_m = tests.quick[k].gap_m};
      const QuickTriangleTest::Answer answer = tests.quick[k].answer;
      bool meet = answer == QuickTriangleTest::Answer::kMeet;
      if (answer == QuickTriangleTest::Answer::kUnknown ||
          answer == QuickTriangleTest::Answer::kEdgesApart) {
        if (const PairHint* apart = tests.HintedApart(k)) {
          hint = *apart;
        } else {
          const PlacedFace& face_a = ia_.leaf_order_faces[candidate.leaf_a];
          const PlacedFace& face_b = faces_b_.Get(candidate.face_b);
          meet = TrianglesIntersect(face_a.triangle, face_a.normal, face_b.triangle, face_b.normal,
                                    margin_, hint);
        }
      }
      candidate.edge_pair = hint.edge_pair;
      if (meet) {
        pairs[found++] = {a, candidate.face_b};
        candidate.apart_until = -1;  // tested again next time
      } else {
        candidate.stream = stream;
        candidate.per_turn_m = Reach(a, candidate.face_b) + hint.lever_m;
        candidate.apart_until = shifted + candidate.per_turn_m * turned + hint.gap_m - rounding;
      }
    }
    pairs.resize(found);
  }

 private:
  struct Entry {
    int id;
    const PlacedFace* face;
  };

  static_assert(kBucketFaces <= BucketBoxes::kCapacity, "one bit per face of a bucket");

  // The candidates of RunCandidates that take a face test, in order, with
  // their faces (A's by leaf, B's by id) and the quick test's answers.
  // The first `size` entries are this query's: the arrays hold at least
  // the most a region can add, so that adding is a store.
  struct FaceTests {
    std::vector<PairCache::Candidate*> candidates;
    std::vector<TrianglePair> faces;
    std::vector<QuickTriangleTest> quick;
    size_t size = 0;

    void Start(size_t most) {
      if (candidates.size() < most) {  // only grown: shrinking would refill
        candidates.resize(most);
        faces.resize(most);
      }
      size = 0;
    }
    void Add(PairCache::Candidate& candidate) {
      candidates[size] = &candidate;
      faces[size] = {candidate.leaf_a, candidate.face_b};
      ++size;
    }
    // The quick test of every pair; for those it leaves with no edge
    // cross kept (new to the region, or kept apart by no edge cross last
    // time), the quick test again with the facing edges' cross (its
    // kMeet, kEdgesApart or kUnknown to `quick`); then the edge cross that
    // last kept apart each pair left with one, or that the second test
    // found. (The second test for every pair new to the region instead of
    // the first: 3 % more instructions on Table 1's #3.)
    void RunQuickTests(const PlacedFace* faces_a, const PlacedFace* faces_b, double margin) {
      if (quick.size() < size) quick.resize(size);
      if (hint_of.size() < size) hint_of.resize(size);
      QuickTrianglesTestBatch(faces_a, faces_b, std::span(faces).first(size), margin,
                              /*edge_cross=*/false, std::span(quick).first(size));
      hinted_faces.clear();
      hints.clear();
      unhinted_faces.clear();
      unhinted.clear();
      for (size_t k = 0; k < size; ++k) {
        if (quick[k].answer != QuickTriangleTest::Answer::kUnknown) continue;
        const int edge_pair = candidates[k]->edge_pair;
        hint_of[k] = -1;
        if (edge_pair >= 0) {
          Hint(k, edge_pair);
        } else {
          unhinted_faces.push_back(faces[k]);
          unhinted.push_back(k);
        }
      }
      if (unhinted_quick.size() < unhinted.size()) unhinted_quick.resize(unhinted.size());
      QuickTrianglesTestBatch(faces_a, faces_b, unhinted_faces, margin, /*edge_cross=*/true,
                              std::span(unhinted_quick).first(unhinted.size()));
      for (size_t n = 0; n < unhinted.size(); ++n) {
        const size_t k = unhinted[n];
        quick[k] = unhinted_quick[n];
        if (quick[k].answer == QuickTriangleTest::Answer::kEdgesApart) Hint(k, quick[k].edge_pair);
      }
      if (separated.size() < hints.size()) separated.resize(hints.size());
      HintedEdgeCrossBatch(faces_a, faces_b, hinted_faces, margin, hints,
                           std::span(separated).first(hints.size()));
    }
    // For a pair k the quick tests leave, or find apart by the facing
    // edges' cross: the hint of that edge cross, or of the one kept, when
    // it keeps the pair apart, else null.
    const PairHint* HintedApart(size_t k) const {
      const int h = hint_of[k];
      return h >= 0 && separated[h] ? &hints[h] : nullptr;
    }

   private:
    // Tries edge cross `edge_pair` for pair k.
    void Hint(size_t k, int edge_pair) {
      hint_of[k] = static_cast<int>(hints.size());
      hinted_faces.push_back(faces[k]);
      hints.push_back({.edge_pair = edge_pair});
    }

    // The edge cross tried for a pair k the quick test leaves:
    // hints[hint_of[k]], or none (-1); not set for the other pairs.
    std::vector<int> hint_of;
    std::vector<TrianglePair> hinted_faces;
    std::vector<PairHint> hints;
    std::vector<uint8_t> separated;
    // The pairs k the first quick test leaves with no edge cross kept,
    // their faces, and the second quick test's answers.
    std::vector<size_t> unhinted;
    std::vector<TrianglePair> unhinted_faces;
    std::vector<QuickTriangleTest> unhinted_quick;
  };

  // A bucket of B's faces placed in A's frame, the degenerate left out,
  // with their boxes, and for a B of one bucket the box of those
  // (PlaceOneBucketOfB).
  struct BucketOfB {
    std::vector<Entry> entries;
    BucketBoxes boxes;
    AxisBox box;
  };

  // Run's lists, kept from bucket to bucket, the face tests it leaves
  // pending (A's face by leaf, B's by id), and RunCandidates' tests.
  struct RunBuffers {
    BucketOfB all_b;  // of B's node last met in this query (all_b_node_)
    std::vector<Entry> list_b;
    BucketBoxes boxes_b;
    std::vector<TrianglePair> pending;
    std::vector<uint8_t> apart;  // KeepCandidates' plane tests
    FaceTests face_tests;
  };

  // B's node `nb` placed (RunBuffers::all_b): again only when the last
  // Run met another node of B. A traversal descending A's hierarchy meets
  // one node of B in many Runs in a row.
  template <typename Node>
  const BucketOfB& PlacedBucketOfB(const Node& nb) const {
    BucketOfB& all_b = buffers_.all_b;
    if (all_b_node_ == &nb) return all_b;
    all_b_node_ = &nb;
    all_b.entries.clear();
    all_b.boxes.Start(margin_);
    for (int i = nb.first_primitive; i < nb.first_primitive + nb.num_primitives; ++i) {
      const int f = ib_.leaf_faces[i];
      if (ib_.degenerate[f]) continue;
      const PlacedFace& face = faces_b_.Get(f);
      all_b.entries.push_back({f, &face});
      all_b.boxes.Add(face.lo.data(), face.hi.data());
    }
    return all_b;
  }

  // A's node `node_a`'s face box (node_face_box), swept.
  AxisBox SweptNodeFaceBox(int node_a) const {
    AxisBox box = ia_.node_face_box[node_a];
    for (int d = 0; d < 3; ++d) {
      box.lo[d] += grow_lo_[d];
      box.hi[d] += grow_hi_[d];
    }
    return box;
  }

  // How far faces `a` of A and `b` of B move per radian of turn.
  double Reach(int a, int b) const { return std::max(ia_.face_reach[a], ib_.face_reach[b]); }

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
    const SkipRun* run = skip_runs_.Find(a);
    return run ? skip_.subspan(run->begin, run->end - run->begin) : std::span<const TrianglePair>();
  }

  // Building a region: the pending pairs that neither face's plane keeps
  // beyond the margin (the region's, slack and all) become candidates, in
  // order; their planes are tested several pairs at a time. A pair left
  // out stays beyond the query's margin while either face moves less than
  // the slack, and the face test's plane tests would reject it.
  void KeepCandidates() const {
    std::vector<TrianglePair>& pending = buffers_.pending;
    std::vector<uint8_t>& apart = buffers_.apart;
    if (apart.size() < pending.size()) apart.resize(pending.size());
    FacePlanesApartBatch(ia_.leaf_order_faces.data(), faces_b_.data(), pending, margin_,
                         std::span(apart).first(pending.size()));
    for (size_t k = 0; k < pending.size(); ++k) {
      if (!apart[k]) candidates_->push_back({pending[k].a, pending[k].b});
    }
    pending.clear();
  }

  const CollisionModel::Impl& ia_;
  const CollisionModel::Impl& ib_;
  const Vector3d* sweep_A_;
  const double margin_;
  const bool planes_only_;
  const std::span<const TrianglePair> skip_;
  std::vector<PairCache::Candidate>* const candidates_;
  PlacedFaces& faces_b_;
  IdMemo<SkipRun>& skip_runs_;
  RunBuffers& buffers_;
  // B's node whose faces buffers_.all_b holds in this query, or null.
  mutable const void* all_b_node_ = nullptr;
  // How far A's face boxes grow when swept: by -sweep_A.
  double grow_lo_[3] = {0, 0, 0}, grow_hi_[3] = {0, 0, 0};
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
  const VolumeTest<BV> volumes(mb, R, T, sweep_A, query.grow_volumes_m);
  const BucketTest buckets(ia, mb, ib, X_AB, sweep_A, query);
  int64_t tests = 0;
  const size_t pairs_before = pairs.size();
  // Kept across calls so that a steady stream of queries does not allocate.
  std::vector<std::pair<int, int>>& stack = Scratch<TraversalStack>().pairs;
  stack.clear();
  stack.emplace_back(0, 0);
  // A small B (a tool, a plate: one bucket) is placed at once, and A's
  // nodes are culled by their face boxes against the box of its faces
  // (ApartFromBucketOfB) instead of the oriented-box test. That test
  // rarely spares a node the face boxes pass: on Table 1's #3 it spared
  // 1 of the 193 those passed, at about 490 instructions a test (8 % of
  // the query). Between two large objects the face boxes spare too few:
  // placing B's buckets to cull by them cost Table 1's #4 8.29M
  // instructions a query against 7.06M.
  const bool b_is_one_bucket = mb.getBV(0).num_primitives <= kBucketFaces;
  if (b_is_one_bucket) buckets.PlaceOneBucketOfB(mb.getBV(0));
  while (!stack.empty()) {
    const auto [i, j] = stack.back();
    stack.pop_back();
    const fcl::BVNode<BV>& na = ma.getBV(i);
    const fcl::BVNode<BV>& nb = mb.getBV(j);
    ++tests;
    const bool small_a = na.num_primitives <= kBucketFaces;
    const bool small_b = nb.num_primitives <= kBucketFaces;
    if (b_is_one_bucket ? buckets.ApartFromBucketOfB(i) : !volumes.Overlap(na.bv, j, nb.bv)) {
      continue;
    }
    if (small_a && small_b) {
      buckets.Run(i, na, nb, pairs);
      if (query.first_only) {
        buckets.TestPending(pairs);
        if (pairs.size() > pairs_before) break;
      }
    } else if (small_b || (!small_a && na.bv.size() >= nb.bv.size())) {
      stack.emplace_back(na.leftChild(), j);
      stack.emplace_back(na.rightChild(), j);
    } else {
      stack.emplace_back(i, nb.leftChild());
      stack.emplace_back(i, nb.rightChild());
    }
  }
  buckets.TestPending(pairs);
  return tests;
}

// A static query through `query.cache`: from the region that holds X_AB,
// built first when none does. Returns the volume tests of the build.
template <typename BV>
int64_t FromRegion(const fcl::BVHModel<BV>& ma, const CollisionModel::Impl& ia,
                   const fcl::BVHModel<BV>& mb, const CollisionModel::Impl& ib,
                   const Isometry3d& X_AB, const Query& query, std::vector<TrianglePair>& pairs) {
  HS_CHECK(!query.sweep_W && !query.first_only);
  int64_t tests = 0;
  PairCache::Region* region = query.cache->Find(ia, ib, query.margin_m, X_AB);
  if (!region) {
    if (!PairCache::Worthwhile(ia, ib, X_AB)) {
      Query plain = query;
      plain.cache = nullptr;
      return Traverse(ma, ia, mb, ib, X_AB, nullptr, plain, pairs);
    }
    PairCache::Region& built = query.cache->Make(ia, ib, query.margin_m, X_AB);
    const double slack = built.skin_m + PairCache::Rounding(ia, ib, built.X_AB);
    Query build = query;
    build.margin_m += slack;
    build.skip = {};
    build.cache = nullptr;
    build.grow_volumes_m = slack;
    build.candidates = &built.candidates;
    tests = Traverse(ma, ia, mb, ib, built.X_AB, nullptr, build, pairs);  // adds no pairs
    region = &built;
  }
  const BucketTest buckets(ia, mb, ib, X_AB, nullptr, query);
  buckets.RunCandidates(*region, PairCache::Rounding(ia, ib, region->X_AB), pairs);
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
        if (query.cache) return FromRegion(*ma, ia, *mb, ib, X_AB, query, pairs);
        return Traverse(*ma, ia, *mb, ib, X_AB, query.sweep_W ? &sweep_A : nullptr, query, pairs);
      },
      ia.bvh);
}

}  // namespace

int64_t FindIntersectingTriangles(const CollisionModel& a, const Isometry3d& X_WA,
                                  const CollisionModel& b, const Isometry3d& X_WB, double margin_m,
                                  std::vector<TrianglePair>& pairs,
                                  std::span<const TrianglePair> skip, PairCache* cache) {
  return Find(a, X_WA, b, X_WB,
              {.sweep_W = nullptr,
               .margin_m = margin_m,
               .first_only = false,
               .face_test = SweptFaceTest::kEveryAxis,
               .skip = skip,
               .cache = cache},
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

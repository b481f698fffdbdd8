#include "common/collision/triangle_pairs.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <span>

#include "common/collision/triangle_sat.h"
#include "common/model/procedural.h"
#include "tests/common/random_poses.h"

namespace hs {
namespace {

using testing_poses::RandomPose;

HapticObject Torus(double major, double minor) {
  return *HapticObject::Create("torus", MakeTorus(major, minor, 24, 12));
}

// The oracle: every face pair through the same SAT leaf test (itself checked
// against CGAL's exact predicate in triangle_sat_test).
std::vector<TrianglePair> BruteForce(const HapticObject& a, const Isometry3d& X_WA,
                                     const HapticObject& b, const Isometry3d& X_WB, double margin) {
  std::vector<TrianglePair> pairs;
  auto world = [](const HapticObject& o, const Isometry3d& X, FaceId f) {
    const auto& v = o.face(f).vertices;
    return Triangle3d{X * o.position(v[0]), X * o.position(v[1]), X * o.position(v[2])};
  };
  for (FaceId fa = 0; fa < a.num_faces(); ++fa) {
    for (FaceId fb = 0; fb < b.num_faces(); ++fb) {
      if (TrianglesIntersect(world(a, X_WA, fa), world(b, X_WB, fb), margin)) {
        pairs.push_back({fa, fb});
      }
    }
  }
  return pairs;
}

std::vector<TrianglePair> Traversal(const CollisionModel& ma, const Isometry3d& X_WA,
                                    const CollisionModel& mb, const Isometry3d& X_WB,
                                    double margin) {
  std::vector<TrianglePair> pairs;
  FindIntersectingTriangles(ma, X_WA, mb, X_WB, margin, pairs);
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

class TrianglePairsTest : public testing::TestWithParam<BvType> {};

// For every bounding volume type the BVH traversal finds exactly the pairs
// of the all-pairs oracle, on random poses of two interlocking tori.
TEST_P(TrianglePairsTest, MatchesBruteForceOnRandomPoses) {
  const HapticObject a = Torus(1.0, 0.3), b = Torus(0.8, 0.25);
  const double margin = 1e-9;
  const CollisionModel ma(a, GetParam(), margin), mb(b, GetParam(), margin);
  std::mt19937 rng(21);
  int colliding_poses = 0;
  for (int i = 0; i < 40; ++i) {
    const Isometry3d X_WA = RandomPose(rng, 0.5), X_WB = RandomPose(rng, 0.5);
    const auto expected = BruteForce(a, X_WA, b, X_WB, margin);
    ASSERT_EQ(Traversal(ma, X_WA, mb, X_WB, margin), expected) << "pose " << i;
    colliding_poses += !expected.empty();
  }
  EXPECT_GT(colliding_poses, 20);
}

// After vertices move, Sync refits the hierarchy and the traversal again
// matches the oracle on the moved geometry.
TEST_P(TrianglePairsTest, SyncRefitsAfterVerticesMove) {
  HapticObject a = Torus(1.0, 0.3);
  const HapticObject b = Torus(0.8, 0.25);
  CollisionModel ma(a, GetParam(), 1e-9);
  const CollisionModel mb(b, GetParam(), 1e-9);
  std::mt19937 rng(22);
  std::normal_distribution<double> noise(0, 0.05);
  std::vector<VertexId> ids;
  std::vector<Vector3d> moved;
  for (VertexId v = 0; v < a.num_vertices(); v += 3) {
    ids.push_back(v);
    moved.push_back(a.position(v) + Vector3d(noise(rng), noise(rng), noise(rng)));
  }
  ASSERT_TRUE(a.MoveVertices(ids, moved).ok());
  EXPECT_TRUE(ma.Sync(a));
  EXPECT_FALSE(ma.Sync(a));
  EXPECT_EQ(ma.geometry_version(), a.geometry_version());
  for (int i = 0; i < 20; ++i) {
    const Isometry3d X_WA = RandomPose(rng, 0.5), X_WB = RandomPose(rng, 0.5);
    ASSERT_EQ(Traversal(ma, X_WA, mb, X_WB, 1e-9), BruteForce(a, X_WA, b, X_WB, 1e-9))
        << "pose " << i;
  }
}

// Two boxes resting face on face (exactly touching, gap 0) are found
// touching at every scale thanks to the grown volumes.
TEST_P(TrianglePairsTest, TouchingBoxesAreFoundAtEveryScale) {
  for (double scale : {1e-4, 1.0, 1e4}) {
    SCOPED_TRACE(scale);
    const HapticObject box = *HapticObject::Create("box", MakeBox(Vector3d::Constant(scale)));
    const double margin = 1e-9 * scale;
    const CollisionModel m(box, GetParam(), margin);
    Isometry3d X_WB = Isometry3d::Identity();
    X_WB.translation() = Vector3d(0.3 * scale, 0.2 * scale, scale);
    const auto pairs = Traversal(m, Isometry3d::Identity(), m, X_WB, margin);
    EXPECT_EQ(pairs, BruteForce(box, Isometry3d::Identity(), box, X_WB, margin));
    EXPECT_FALSE(pairs.empty());
    X_WB.translation().z() += 1e-6 * scale;
    EXPECT_TRUE(Traversal(m, Isometry3d::Identity(), m, X_WB, margin).empty());
  }
}

// Swept queries find exactly the pairs whose sweep interval meets the
// motion (all-pairs oracle), and every pair seen intersecting at sampled
// instants of the motion is among them. Asked for the planes only, they
// find those and pairs whose face planes' bounds meet the motion.
TEST_P(TrianglePairsTest, SweptQueryMatchesOracles) {
  const HapticObject a = Torus(1.0, 0.3), b = Torus(0.8, 0.25);
  const CollisionModel ma(a, GetParam(), 1e-9), mb(b, GetParam(), 1e-9);
  std::mt19937 rng(23);
  std::normal_distribution<double> n(0, 0.3);
  size_t extra_candidates = 0;
  for (int i = 0; i < 15; ++i) {
    const Isometry3d X_WA = RandomPose(rng, 0.8), X_WB = RandomPose(rng, 0.8);
    const Vector3d sweep(n(rng), n(rng), n(rng));
    std::vector<TrianglePair> swept;
    FindSweptTrianglePairs(ma, X_WA, sweep, mb, X_WB, 1e-9, swept);
    std::sort(swept.begin(), swept.end());
    std::vector<TrianglePair> oracle;
    for (FaceId fa = 0; fa < a.num_faces(); ++fa) {
      const auto& va = a.face(fa).vertices;
      const Triangle3d ta = {X_WA * a.position(va[0]), X_WA * a.position(va[1]),
                             X_WA * a.position(va[2])};
      for (FaceId fb = 0; fb < b.num_faces(); ++fb) {
        const auto& vb = b.face(fb).vertices;
        const Triangle3d tb = {X_WB * b.position(vb[0]), X_WB * b.position(vb[1]),
                               X_WB * b.position(vb[2])};
        if (SweptIntersection(ta, tb, sweep, 1e-9).Overlaps(0, 1)) oracle.push_back({fa, fb});
      }
    }
    ASSERT_EQ(swept, oracle) << "pose " << i;
    // Planes only: every pair of the oracle, and the others only where
    // the two face planes do not rule the pair out over the motion.
    std::vector<TrianglePair> candidates;
    FindSweptTrianglePairs(ma, X_WA, sweep, mb, X_WB, 1e-9, candidates, {},
                           SweptFaceTest::kPlanesOnly);
    std::sort(candidates.begin(), candidates.end());
    ASSERT_TRUE(std::includes(candidates.begin(), candidates.end(), oracle.begin(), oracle.end()))
        << "pose " << i;
    for (const TrianglePair& p : candidates) {
      const auto& va = a.face(p.a).vertices;
      const auto& vb = b.face(p.b).vertices;
      const Triangle3d ta = {X_WA * a.position(va[0]), X_WA * a.position(va[1]),
                             X_WA * a.position(va[2])};
      const Triangle3d tb = {X_WB * b.position(vb[0]), X_WB * b.position(vb[1]),
                             X_WB * b.position(vb[2])};
      // Computed in the world frame, not the traversal's: rounding apart.
      EXPECT_FALSE(SweptPlaneBounds(ta, tb, sweep, 1e-6, {-1e-6, 1 + 1e-6}).within_margin.empty())
          << "pose " << i;
    }
    extra_candidates += candidates.size() - oracle.size();
    for (double s : {0.0, 0.25, 0.5, 0.75, 1.0}) {
      Isometry3d X = X_WA;
      X.pretranslate(-s * sweep);
      for (const TrianglePair& p : Traversal(ma, X, mb, X_WB, 1e-9)) {
        EXPECT_TRUE(std::binary_search(swept.begin(), swept.end(), p))
            << "pose " << i << " s " << s;
      }
    }
  }
  EXPECT_GT(extra_candidates, 0u);  // the planes alone are a looser test
}

// Pairs the caller has decided already are left out, and only they: every
// other pair of the oracle is still found, whichever model is the larger
// (the traversal turns round to lead with it), static or swept.
TEST_P(TrianglePairsTest, SkippedPairsAreLeftOut) {
  const HapticObject small = Torus(1.0, 0.3);
  const HapticObject large = *HapticObject::Create("large", MakeTorus(0.8, 0.25, 40, 20));
  const CollisionModel ms(small, GetParam(), 1e-9), ml(large, GetParam(), 1e-9);
  std::mt19937 rng(24);
  int checked = 0;
  for (int i = 0; i < 20; ++i) {
    const Isometry3d X_WA = RandomPose(rng, 0.5), X_WB = RandomPose(rng, 0.5);
    const Vector3d sweep = 0.05 * RandomPose(rng, 1.0).translation();
    for (const bool small_first : {true, false}) {
      const CollisionModel& ma = small_first ? ms : ml;
      const CollisionModel& mb = small_first ? ml : ms;
      const FaceId last_a = (small_first ? small : large).num_faces() - 1;
      const FaceId last_b = (small_first ? large : small).num_faces() - 1;
      for (const bool swept : {false, true}) {
        auto find = [&](std::span<const TrianglePair> skip) {
          std::vector<TrianglePair> pairs;
          if (swept) {
            FindSweptTrianglePairs(ma, X_WA, sweep, mb, X_WB, 1e-9, pairs, skip);
          } else {
            FindIntersectingTriangles(ma, X_WA, mb, X_WB, 1e-9, pairs, skip);
          }
          std::sort(pairs.begin(), pairs.end());
          return pairs;
        };
        const std::vector<TrianglePair> all = find({});
        // Skip every other pair, and a pair that is not there at all.
        std::vector<TrianglePair> skip, rest;
        for (size_t k = 0; k < all.size(); ++k) (k % 2 == 0 ? skip : rest).push_back(all[k]);
        skip.push_back({last_a, last_b});
        std::sort(skip.begin(), skip.end());
        skip.erase(std::unique(skip.begin(), skip.end()), skip.end());
        rest.erase(std::remove_if(rest.begin(), rest.end(),
                                  [&](const TrianglePair& p) {
                                    return std::binary_search(skip.begin(), skip.end(), p);
                                  }),
                   rest.end());
        ASSERT_EQ(find(skip), rest)
            << "pose " << i << " small first " << small_first << " swept " << swept;
        checked += !rest.empty();
      }
    }
  }
  EXPECT_GT(checked, 20);
}

// A tool of one bucket of faces (a 12-face box) against a large object,
// which the traversal culls by the boxes of the large object's nodes'
// faces once the tool's faces are placed: exactly the oracles' pairs,
// static at two margins and swept, with the tool on either side and at
// poses around the tube where it touches, pokes in or stays clear, and
// lying flat half a millimetre above the tube's top ridge (found only
// within the larger margin: a cull a centimetre too strict loses them).
TEST_P(TrianglePairsTest, AOneBucketToolAgainstALargeObjectMatchesTheOracles) {
  const HapticObject torus = Torus(1.0, 0.3);
  const HapticObject tool = *HapticObject::Create("tool", MakeBox(Vector3d(0.4, 0.1, 0.05)));
  std::mt19937 rng(25);
  std::uniform_real_distribution<double> u(-1, 1);
  int colliding = 0, clear = 0, grazing = 0;
  for (const double margin : {1e-9, 1e-3}) {
    const CollisionModel mt(torus, GetParam(), margin), mk(tool, GetParam(), margin);
    for (int i = 0; i < 20; ++i) {
      Isometry3d X_WK;
      if (i < 16) {
        const double angle = 3.2 * u(rng), radius = 1.3 + 0.35 * u(rng);
        X_WK = RandomPose(rng, 0.05);
        X_WK.pretranslate(
            Vector3d(radius * std::cos(angle), radius * std::sin(angle), 0.1 * u(rng)));
      } else {  // flat on the ridge of the top vertices (z = 0.3, radius 1)
        const double angle = 0.3 + 1.4 * i;
        X_WK = Isometry3d::Identity();
        X_WK.translate(Vector3d(std::cos(angle), std::sin(angle), 0.3 + 0.025 + 5e-4));
        X_WK.rotate(Eigen::AngleAxisd(angle + 1.5, Vector3d::UnitZ()));
      }
      const Isometry3d X_WT = Isometry3d::Identity();
      const auto expected = BruteForce(torus, X_WT, tool, X_WK, margin);
      ASSERT_EQ(Traversal(mt, X_WT, mk, X_WK, margin), expected) << "pose " << i;
      std::vector<TrianglePair> reversed = Traversal(mk, X_WK, mt, X_WT, margin);
      for (TrianglePair& pair : reversed) std::swap(pair.a, pair.b);
      std::sort(reversed.begin(), reversed.end());
      ASSERT_EQ(reversed, expected) << "pose " << i;
      (expected.empty() ? clear : colliding) += 1;
      grazing += i >= 16 && !expected.empty();
      const Vector3d sweep = 0.1 * Vector3d(u(rng), u(rng), u(rng));
      std::vector<TrianglePair> swept;
      FindSweptTrianglePairs(mt, X_WT, sweep, mk, X_WK, margin, swept);
      std::sort(swept.begin(), swept.end());
      std::vector<TrianglePair> oracle;
      for (FaceId ft = 0; ft < torus.num_faces(); ++ft) {
        for (FaceId fk = 0; fk < tool.num_faces(); ++fk) {
          const auto &vt = torus.face(ft).vertices, &vk = tool.face(fk).vertices;
          const Triangle3d tt = {torus.position(vt[0]), torus.position(vt[1]),
                                 torus.position(vt[2])};
          const Triangle3d tk = {X_WK * tool.position(vk[0]), X_WK * tool.position(vk[1]),
                                 X_WK * tool.position(vk[2])};
          if (SweptIntersection(tt, tk, sweep, margin).Overlaps(0, 1)) oracle.push_back({ft, fk});
        }
      }
      ASSERT_EQ(swept, oracle) << "pose " << i << " swept";
    }
  }
  EXPECT_GT(colliding, 8);
  EXPECT_GT(clear, 2);
  EXPECT_EQ(grazing, 4);  // at the larger margin only
}

// A small cube passing through a thin plate in one step: no pair at the
// end pose, but the swept query finds the plate.
TEST_P(TrianglePairsTest, SweptQueryCatchesPassThrough) {
  const HapticObject plate = *HapticObject::Create("plate", MakeBox(Vector3d(2, 2, 0.01)));
  const HapticObject cube = *HapticObject::Create("cube", MakeBox(Vector3d(0.1, 0.1, 0.1)));
  const CollisionModel mp(plate, GetParam(), 1e-9), mc(cube, GetParam(), 1e-9);
  Isometry3d X_end = Isometry3d::Identity();
  X_end.translation() = Vector3d(0.3, 0.2, -0.5);
  EXPECT_TRUE(Traversal(mc, X_end, mp, Isometry3d::Identity(), 1e-9).empty());
  std::vector<TrianglePair> swept;
  FindSweptTrianglePairs(mc, X_end, Vector3d(0, 0, -1), mp, Isometry3d::Identity(), 1e-9, swept);
  EXPECT_FALSE(swept.empty());
}

INSTANTIATE_TEST_SUITE_P(AllBvTypes, TrianglePairsTest,
                         testing::Values(BvType::kObbRss, BvType::kObb, BvType::kRss, BvType::kKios,
                                         BvType::kAabb),
                         [](const auto& info) { return std::string(BvTypeName(info.param)); });

// Names round-trip and unknown names are rejected.
TEST(BvTypeTest, ParseAndName) {
  for (BvType t : {BvType::kObbRss, BvType::kObb, BvType::kRss, BvType::kKios, BvType::kAabb}) {
    EXPECT_EQ(*ParseBvType(BvTypeName(t)), t);
  }
  EXPECT_EQ(ParseBvType("sphere").status().code(), absl::StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace hs

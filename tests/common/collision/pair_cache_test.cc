#include "common/collision/pair_cache.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>
#include <vector>

#include "common/collision/fcl_bvh.h"
#include "common/collision/triangle_pairs.h"
#include "common/model/procedural.h"
#include "tests/common/random_poses.h"

namespace hs {
namespace {

using testing_poses::RandomPose;

HapticObject Torus(double major, double minor, int segments = 24, int sides = 12) {
  return *HapticObject::Create("torus", MakeTorus(major, minor, segments, sides));
}

// The oracle is the query from scratch: the same call without a cache
// (itself matched against every face pair in triangle_pairs_test).
std::vector<TrianglePair> FromScratch(const CollisionModel& ma, const Isometry3d& X_WA,
                                      const CollisionModel& mb, const Isometry3d& X_WB,
                                      double margin, std::span<const TrianglePair> skip = {}) {
  std::vector<TrianglePair> pairs;
  FindIntersectingTriangles(ma, X_WA, mb, X_WB, margin, pairs, skip);
  return pairs;
}

std::vector<TrianglePair> Cached(PairCache& cache, const CollisionModel& ma, const Isometry3d& X_WA,
                                 const CollisionModel& mb, const Isometry3d& X_WB, double margin,
                                 std::span<const TrianglePair> skip = {}) {
  std::vector<TrianglePair> pairs;
  FindIntersectingTriangles(ma, X_WA, mb, X_WB, margin, pairs, skip, &cache);
  return pairs;
}

// A hand-held tool's path: from X0, sliding along x at `speed` m/s and
// turning about the vertical at 1 rad/s, one pose per millisecond.
std::vector<Isometry3d> CoherentPath(const Isometry3d& X0, double speed, int steps) {
  std::vector<Isometry3d> path;
  for (int k = 0; k < steps; ++k) {
    const double t = 0.001 * k;
    Isometry3d X = X0;
    X.translation().x() += speed * t;
    X.linear() = Eigen::AngleAxisd(t, Vector3d::UnitZ()).toRotationMatrix() * X0.linear();
    path.push_back(X);
  }
  return path;
}

// The second torus above the first, tilted, their tubes cutting each other
// along two closed curves: they stay in contact along CoherentPath.
Isometry3d Overlapping() {
  Isometry3d X = Isometry3d::Identity();
  X.translation() = Vector3d(0.3, 0, 0.2);
  X.rotate(Eigen::AngleAxisd(0.1, Vector3d::UnitX()));
  return X;
}

class PairCacheTest : public testing::TestWithParam<BvType> {};

// Along a coherent path through two interlocking tori, every query answers
// exactly as from scratch, pairs and order, and most come from a region.
TEST_P(PairCacheTest, CoherentPathMatchesTheQueryFromScratch) {
  const HapticObject a = Torus(1.0, 0.3), b = Torus(0.8, 0.25);
  const double margin = 1e-9;
  const CollisionModel ma(a, GetParam(), 1e-6), mb(b, GetParam(), 1e-6);
  PairCache cache;
  int touching = 0;
  const std::vector<Isometry3d> path = CoherentPath(Overlapping(), 0.1, 500);
  for (size_t k = 0; k < path.size(); ++k) {
    const auto expected = FromScratch(ma, Isometry3d::Identity(), mb, path[k], margin);
    ASSERT_EQ(Cached(cache, ma, Isometry3d::Identity(), mb, path[k], margin), expected)
        << "step " << k;
    touching += !expected.empty();
  }
  EXPECT_EQ(touching, 500);
  EXPECT_LT(cache.builds(), 100);
  EXPECT_EQ(cache.builds() + cache.hits(), 500);
}

// Two tori along a steady coherent path, and how many skins' worth of
// motion it takes: regions built at the pose would need a build for each.
class PairCacheBuildTest : public testing::Test {
 protected:
  // The pairs at B's pose X_AB in A's frame, from scratch and through the
  // cache, those in `skip` left out.
  std::vector<TrianglePair> FromScratchAt(const Isometry3d& X_AB,
                                          std::span<const TrianglePair> skip = {}) const {
    return FromScratch(ma_, Isometry3d::Identity(), mb_, X_AB, kMargin, skip);
  }
  std::vector<TrianglePair> CachedAt(const Isometry3d& X_AB,
                                     std::span<const TrianglePair> skip = {}) {
    return Cached(cache_, ma_, Isometry3d::Identity(), mb_, X_AB, kMargin, skip);
  }
  // The sum of the path's steps' motion bounds over the skin.
  double SkinsOfMotion() const {
    double motion = 0;
    for (size_t k = 1; k < path_.size(); ++k) {
      motion += RelativeMotionBound(ma_.impl(), mb_.impl(), path_[k - 1], path_[k]);
    }
    return motion / (PairCache::kSkinRelative * (ma_.impl().radius + mb_.impl().radius));
  }

  static constexpr double kMargin = 1e-9;
  const HapticObject a_ = Torus(1.0, 0.3), b_ = Torus(0.8, 0.25);
  const CollisionModel ma_{a_, BvType::kObbRss, 1e-6}, mb_{b_, BvType::kObbRss, 1e-6};
  const std::vector<Isometry3d> path_ = CoherentPath(Overlapping(), 0.1, 500);
  PairCache cache_;
};

// A steady motion leaves each region after crossing the skin's whole
// width: regions are built ahead of the pose along the motion, so there
// are far fewer builds than the motion over the skin, and every answer is
// still the one from scratch.
TEST_F(PairCacheBuildTest, SteadyMotionBuildsAheadOfThePose) {
  for (size_t k = 0; k < path_.size(); ++k) {
    ASSERT_EQ(CachedAt(path_[k]), FromScratchAt(path_[k])) << "step " << k;
  }
  EXPECT_GT(SkinsOfMotion(), 20);
  EXPECT_LT(cache_.builds(), 0.7 * SkinsOfMotion());
}

// A contact's two queries a step, at its pose and at its depth (the pose
// moved back along the approach by 2-6 mm, varying smoothly, within the
// skin of 19 mm), share a region, alternately. Each run of queries keeps
// its own travel: every answer is the one from scratch, with every other
// pair found at the pose skipped at the depth (as the sweep skips the
// pairs it knows), and the steady motion of the pose still builds regions
// ahead of it.
TEST_F(PairCacheBuildTest, PoseAndDepthQueriesInTurnMatchTheQueryFromScratch) {
  for (size_t k = 0; k < path_.size(); ++k) {
    const std::vector<TrianglePair> at_pose = FromScratchAt(path_[k]);
    ASSERT_EQ(CachedAt(path_[k]), at_pose) << "step " << k;
    std::vector<TrianglePair> known;
    for (size_t i = 0; i < at_pose.size(); i += 2) known.push_back(at_pose[i]);
    Isometry3d at_depth = path_[k];
    at_depth.pretranslate(Vector3d(0, 0, 0.004 + 0.002 * std::sin(0.02 * k)));
    ASSERT_EQ(CachedAt(at_depth, known), FromScratchAt(at_depth, known)) << "step " << k;
  }
  EXPECT_LT(cache_.builds(), 0.7 * SkinsOfMotion());
}

// A cache restarted with a skin builds its next regions with that skin, as
// ComputeContact's own cache does for the two pair queries of one contact
// query: queries backed out by less than the skin from the first come from
// its region, the one at the pose with the known pairs skipped too, and
// one backed out further builds a second; every answer is the query's from
// scratch. A cache never restarted has DefaultSkin.
TEST_P(PairCacheTest, RestartSetsTheSkinOfTheNextRegions) {
  const HapticObject a = Torus(1.0, 0.3), b = Torus(0.8, 0.25);
  const double margin = 1e-9;
  const CollisionModel ma(a, GetParam(), 1e-6), mb(b, GetParam(), 1e-6);
  const double skin = 0.25 * PairCache::DefaultSkin(ma, mb);
  const Vector3d back = Vector3d(0.3, -0.2, 0.9).normalized();
  const auto backed_out = [&](double t) {
    Isometry3d X = Overlapping();
    X.pretranslate(t * back);
    return X;
  };
  PairCache cache;
  cache.Restart(skin);
  const std::vector<TrianglePair> at_pose =
      Cached(cache, ma, Isometry3d::Identity(), mb, backed_out(0), margin);
  ASSERT_FALSE(at_pose.empty());
  EXPECT_EQ(at_pose, FromScratch(ma, Isometry3d::Identity(), mb, backed_out(0), margin));
  std::vector<TrianglePair> known = at_pose;
  std::ranges::sort(known);
  for (const double t : {0.5 * skin, 0.99 * skin}) {
    EXPECT_EQ(Cached(cache, ma, Isometry3d::Identity(), mb, backed_out(t), margin, known),
              FromScratch(ma, Isometry3d::Identity(), mb, backed_out(t), margin, known))
        << "backed out by " << t;
  }
  EXPECT_EQ(cache.builds(), 1);
  EXPECT_EQ(cache.hits(), 2);
  EXPECT_EQ(Cached(cache, ma, Isometry3d::Identity(), mb, backed_out(1.5 * skin), margin),
            FromScratch(ma, Isometry3d::Identity(), mb, backed_out(1.5 * skin), margin));
  EXPECT_EQ(cache.builds(), 2);
  cache.Restart(skin);  // forgets both regions
  EXPECT_EQ(cache.regions(), 0);

  PairCache by_default;
  const double default_skin = PairCache::DefaultSkin(ma, mb);
  EXPECT_EQ(default_skin, PairCache::kSkinRelative * (ma.impl().radius + mb.impl().radius));
  for (const double t : {0.0, 0.99 * default_skin, 1.5 * default_skin}) {
    EXPECT_EQ(Cached(by_default, ma, Isometry3d::Identity(), mb, backed_out(t), margin),
              FromScratch(ma, Isometry3d::Identity(), mb, backed_out(t), margin))
        << "backed out by " << t;
  }
  EXPECT_EQ(by_default.builds(), 2);
  EXPECT_EQ(by_default.hits(), 1);
}

// Random jumps: every query far from the last builds a region, and still
// answers as from scratch, with the larger mesh first or second (the
// traversal turns round to lead with it) and with pairs skipped.
TEST_P(PairCacheTest, RandomJumpsAndSkippedPairsMatchTheQueryFromScratch) {
  const HapticObject small = Torus(1.0, 0.3);
  const HapticObject large = Torus(0.8, 0.25, 40, 20);
  const double margin = 1e-9;
  const CollisionModel ms(small, GetParam(), 1e-6), ml(large, GetParam(), 1e-6);
  std::mt19937 rng(31);
  PairCache small_first, large_first;
  int touching = 0;
  for (int i = 0; i < 40; ++i) {
    const Isometry3d X_WA = RandomPose(rng, 0.5), X_WB = RandomPose(rng, 0.5);
    const auto expected = FromScratch(ms, X_WA, ml, X_WB, margin);
    ASSERT_EQ(Cached(small_first, ms, X_WA, ml, X_WB, margin), expected) << "pose " << i;
    ASSERT_EQ(Cached(large_first, ml, X_WB, ms, X_WA, margin),
              FromScratch(ml, X_WB, ms, X_WA, margin))
        << "pose " << i;
    // Every other pair found skipped: the rest are found, as from scratch.
    std::vector<TrianglePair> skip;
    for (size_t k = 0; k < expected.size(); k += 2) skip.push_back(expected[k]);
    std::sort(skip.begin(), skip.end());
    ASSERT_EQ(Cached(small_first, ms, X_WA, ml, X_WB, margin, skip),
              FromScratch(ms, X_WA, ml, X_WB, margin, skip))
        << "pose " << i;
    touching += !expected.empty();
  }
  EXPECT_GT(touching, 20);
}

// Boxes resting face on face (gap 0), sliding and turning on each other at
// 1e-4, 1 and 1e4 m: the touching pairs, coplanar and all, as from scratch
// at every step; lifted by twice the margin, none.
TEST_P(PairCacheTest, TouchingBoxesSlideAsFromScratchAtEveryScale) {
  for (const double scale : {1e-4, 1.0, 1e4}) {
    SCOPED_TRACE(scale);
    const HapticObject box = *HapticObject::Create("box", MakeBox(Vector3d::Constant(scale)));
    const double margin = 1e-9 * scale;
    const CollisionModel m(box, GetParam(), 1e-6 * scale);
    Isometry3d X0 = Isometry3d::Identity();
    X0.translation() = Vector3d(0.3 * scale, 0.2 * scale, scale);
    PairCache cache;
    int touching = 0;
    for (const Isometry3d& X : CoherentPath(X0, 0.1 * scale, 200)) {
      const auto expected = FromScratch(m, Isometry3d::Identity(), m, X, margin);
      ASSERT_EQ(Cached(cache, m, Isometry3d::Identity(), m, X, margin), expected);
      touching += !expected.empty();
      Isometry3d lifted = X;
      lifted.translation().z() += 2 * margin;
      ASSERT_TRUE(Cached(cache, m, Isometry3d::Identity(), m, lifted, margin).empty());
    }
    EXPECT_EQ(touching, 200);
  }
}

// Far from the origin the pair query works in A's frame, where the
// coordinates are small: regions serve there too. Two objects far from each
// other would make rounding's share of a region's slack (it grows with the
// coordinates) larger than the objects, a region of nearly every pair: none
// is built, and the query runs from scratch. The answers are those from
// scratch throughout.
TEST_P(PairCacheTest, FarFromTheOriginAndFromEachOtherAnswersAsFromScratch) {
  const HapticObject a = Torus(1.0, 0.3), b = Torus(0.8, 0.25);
  const CollisionModel ma(a, GetParam(), 1e-6), mb(b, GetParam(), 1e-6);
  Isometry3d X_WA = Isometry3d::Identity();
  X_WA.translation() = Vector3d(1e10, -1e10, 1e10);
  PairCache cache;
  int touching = 0;
  for (const Isometry3d& X : CoherentPath(Overlapping(), 0.1, 20)) {
    const Isometry3d X_WB = X_WA * X;
    const auto expected = FromScratch(ma, X_WA, mb, X_WB, 1e-9);
    ASSERT_EQ(Cached(cache, ma, X_WA, mb, X_WB, 1e-9), expected);
    touching += !expected.empty();
  }
  EXPECT_EQ(touching, 20);
  EXPECT_GT(cache.hits(), 10);
  cache.Clear();
  Isometry3d apart = Overlapping();
  apart.translation().x() += 1e12;
  EXPECT_TRUE(Cached(cache, ma, Isometry3d::Identity(), mb, apart, 1e-9).empty());
  EXPECT_EQ(cache.regions(), 0);
}

// Moved vertices (a new geometry version) and another margin each build a
// region of their own: the answers stay those from scratch.
TEST_P(PairCacheTest, GeometryAndMarginChangesBuildNewRegions) {
  HapticObject a = Torus(1.0, 0.3);
  const HapticObject b = Torus(0.8, 0.25);
  CollisionModel ma(a, GetParam(), 1e-6);
  const CollisionModel mb(b, GetParam(), 1e-6);
  const Isometry3d X_WB = Overlapping();
  PairCache cache;
  ASSERT_EQ(Cached(cache, ma, Isometry3d::Identity(), mb, X_WB, 1e-9),
            FromScratch(ma, Isometry3d::Identity(), mb, X_WB, 1e-9));
  ASSERT_EQ(Cached(cache, ma, Isometry3d::Identity(), mb, X_WB, 1e-7),
            FromScratch(ma, Isometry3d::Identity(), mb, X_WB, 1e-7));
  EXPECT_EQ(cache.builds(), 2);
  std::vector<VertexId> ids;
  std::vector<Vector3d> moved;
  for (VertexId v = 0; v < a.num_vertices(); v += 2) {
    ids.push_back(v);
    moved.push_back(1.05 * a.position(v));
  }
  ASSERT_TRUE(a.MoveVertices(ids, moved).ok());
  ASSERT_TRUE(ma.Sync(a));
  const auto expected = FromScratch(ma, Isometry3d::Identity(), mb, X_WB, 1e-9);
  EXPECT_EQ(Cached(cache, ma, Isometry3d::Identity(), mb, X_WB, 1e-9), expected);
  EXPECT_EQ(cache.builds(), 3);
  EXPECT_FALSE(expected.empty());
  cache.Clear();
  EXPECT_EQ(cache.regions(), 0);
}

// Two tori, and pairs of B's poses in A's frame, from and to: small steps
// (a 0.1 mm shift and a 1 mrad turn) and large jumps, alternately.
class RelativeMotionBoundTest : public testing::Test {
 protected:
  RelativeMotionBoundTest() {
    for (int i = 0; i < 50; ++i) {
      const Isometry3d from = RandomPose(rng, 2.0);
      Isometry3d to = from;
      if (i % 2 == 0) {
        to.pretranslate(1e-4 * RandomPose(rng, 1.0).translation());
        to.rotate(Eigen::AngleAxisd(1e-3, testing_poses::RandomDirection(rng)));
      } else {
        to = RandomPose(rng, 2.0);
      }
      moves.emplace_back(from, to);
    }
  }

  const HapticObject a = Torus(1.0, 0.3), b = Torus(0.8, 0.25, 40, 20);
  const CollisionModel ma{a, BvType::kObbRss, 1e-6}, mb{b, BvType::kObbRss, 1e-6};
  std::mt19937 rng{32};
  std::vector<std::pair<Isometry3d, Isometry3d>> moves;
};

// The motion bound holds every vertex's motion (the oracle: each vertex of
// A moved in B's frame, of B in A's), from small turns to large jumps, and
// is zero for no motion.
TEST_F(RelativeMotionBoundTest, BoundsEveryVertexMotion) {
  for (size_t i = 0; i < moves.size(); ++i) {
    const auto& [from, to] = moves[i];
    const double bound = RelativeMotionBound(ma.impl(), mb.impl(), from, to);
    double most = 0;
    for (const Vector3d& p : b.positions()) most = std::max(most, (to * p - from * p).norm());
    for (const Vector3d& p : a.positions()) {
      most = std::max(most, (to.inverse() * p - from.inverse() * p).norm());
    }
    EXPECT_LE(most, bound) << "pose " << i;
    EXPECT_LE(bound, 3 * most + 1e-12) << "pose " << i;  // not needlessly loose
  }
  const Isometry3d X = RandomPose(rng, 2.0);
  EXPECT_EQ(RelativeMotionBound(ma.impl(), mb.impl(), X, X), 0);
}

// The per-face bound a region spends its pairs' gaps by: each face's
// corners (of B in A's frame, of A in B's) move at most the centres' shift
// plus the face's reach times the turn, and every direction fixed to B
// turns by at most the turn; a face's reach is at most its model's radius,
// and on a torus most are well inside it.
TEST_F(RelativeMotionBoundTest, FaceReachBoundsEachFacesMotion) {
  for (size_t i = 0; i < moves.size(); ++i) {
    const auto& [from, to] = moves[i];
    const double shift = RelativeShift(ma.impl(), mb.impl(), from, to);
    const double turn = RelativeTurn(from, to);
    for (int f = 0; f < b.num_faces(); ++f) {
      for (const VertexId v : b.face(f).vertices) {
        const Vector3d& p = b.position(v);
        ASSERT_LE((to * p - from * p).norm(), shift + mb.impl().face_reach[f] * turn)
            << "pose " << i << " face " << f;
      }
    }
    for (int f = 0; f < a.num_faces(); ++f) {
      for (const VertexId v : a.face(f).vertices) {
        const Vector3d& p = a.position(v);
        ASSERT_LE((to.inverse() * p - from.inverse() * p).norm(),
                  shift + ma.impl().face_reach[f] * turn)
            << "pose " << i << " face " << f;
      }
    }
    for (int k = 0; k < 10; ++k) {
      const Vector3d u = testing_poses::RandomDirection(rng);
      EXPECT_LE((to.linear() * u - from.linear() * u).norm(), turn * (1 + 1e-12)) << i;
    }
  }
  int inside = 0;
  for (const double reach : mb.impl().face_reach) {
    EXPECT_LE(reach, mb.impl().radius);
    inside += reach < 0.9 * mb.impl().radius;
  }
  EXPECT_GT(inside, b.num_faces() / 4);
}

INSTANTIATE_TEST_SUITE_P(AllVolumes, PairCacheTest,
                         testing::Values(BvType::kObbRss, BvType::kObb, BvType::kRss, BvType::kKios,
                                         BvType::kAabb),
                         [](const testing::TestParamInfo<BvType>& info) {
                           return std::string(BvTypeName(info.param));
                         });

}  // namespace
}  // namespace hs

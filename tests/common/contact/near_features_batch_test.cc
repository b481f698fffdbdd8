// The contact locator's first tests in lanes give the scalar comparisons'
// answers (their definition, near_features_oracle.h) pair by pair
// on every SIMD target built in, and tell what a hand-placed pair has near.

#include "common/contact/near_features_batch.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "hwy/targets.h"
#include "tests/common/collision/sample_triangles.h"
#include "tests/common/contact/near_features_oracle.h"

namespace hs {
namespace {

using testing::NearFeaturesOracle;
using testing::SameNearFeatures;

std::string Bits(const NearFeatures& x) {
  return std::to_string(x.moving_corners) + " " + std::to_string(x.moving_edges) + " " +
         std::to_string(x.fixed_corners) + " " + std::to_string(x.fixed_edges);
}

// Every pair (moving[i % moving.size()], fixed[i % fixed.size()]) through
// the batch on every target, against the oracle; returns the oracle's
// answers.
std::vector<NearFeatures> ExpectOracleAnswers(const std::vector<Triangle3d>& moving_corners,
                                              const std::vector<Triangle3d>& fixed_corners,
                                              double tol, double slack) {
  std::vector<MovingFaceCorners> moving;
  for (const Triangle3d& t : moving_corners) moving.push_back({t});
  std::vector<FixedFaceEdges> fixed;
  for (const Triangle3d& t : fixed_corners) fixed.emplace_back(t);
  const size_t n = std::max(moving.size(), fixed.size());
  std::vector<FaceRecordPair> pairs;
  std::vector<NearFeatures> oracle;
  for (size_t i = 0; i < n; ++i) {
    const auto m = static_cast<int32_t>(i % moving.size()),
               f = static_cast<int32_t>(i % fixed.size());
    pairs.push_back({m, f});
    oracle.push_back(NearFeaturesOracle(moving[m].corners, fixed[f], tol, slack));
  }
  for (const int64_t target : hwy::SupportedAndGeneratedTargets()) {
    hwy::SetSupportedTargetsForTest(target);
    SCOPED_TRACE(hwy::TargetName(target));
    std::vector<NearFeatures> out(n, {7, 7, 7, 7});
    NearFeaturesBatch(moving.data(), fixed.data(), pairs, tol, slack, out);
    for (size_t i = 0; i < n; ++i) {
      EXPECT_TRUE(SameNearFeatures(out[i], oracle[i]))
          << "pair " << i << " of " << n << ": batch " << Bits(out[i]) << "; oracle "
          << Bits(oracle[i]);
    }
  }
  hwy::SetSupportedTargetsForTest(0);
  return oracle;
}

// Small moving faces near, on and across large fixed ones, at tiny, unit
// and huge scales, every batch size from 1 to 19 pairs: every bit of every
// field is set for some pair and clear for another.
TEST(NearFeaturesBatchTest, RandomFacesGiveTheOracleAnswers) {
  std::mt19937 rng(41);
  std::uniform_real_distribution<double> u(-1, 1);
  int set[4][3] = {}, pairs = 0;
  for (const double scale : {1e-6, 1.0, 1e4}) {
    for (size_t n = 1; n <= 19; ++n) {
      std::vector<Triangle3d> moving, fixed;
      for (size_t i = 0; i < n; ++i) {
        const Triangle3d f = testing::RandomTriangle(rng, scale, Vector3d::Zero());
        fixed.push_back(f);
        // A tenth of the fixed face's size, about a point of its plane or,
        // every third pair, about one of its corners in turn; with a corner
        // pressed onto its plane in every other pair.
        const double s = 0.5 * (u(rng) + 1), t = 0.5 * (u(rng) + 1);
        const Vector3d at =
            i % 3 == 2 ? f[i / 3 % 3] : f[0] + s * (f[1] - f[0]) + t * (f[2] - f[0]);
        Triangle3d m = testing::RandomTriangle(rng, 0.1 * scale, at);
        if (i % 2 == 0) {
          const Vector3d normal = UnitNormal(f);
          m[i % 3] -= normal * normal.dot(m[i % 3] - f[0]);
        }
        moving.push_back(m);
      }
      const double tol = 1e-3 * scale;
      for (const NearFeatures& x : ExpectOracleAnswers(moving, fixed, tol, 2 * tol)) {
        const uint8_t fields[4] = {x.moving_corners, x.moving_edges, x.fixed_corners,
                                   x.fixed_edges};
        for (int k = 0; k < 4; ++k) {
          for (int b = 0; b < 3; ++b) set[k][b] += fields[k] >> b & 1;
        }
        ++pairs;
      }
    }
  }
  for (int k = 0; k < 4; ++k) {
    for (int b = 0; b < 3; ++b) {
      EXPECT_GT(set[k][b], 0) << "field " << k << " bit " << b;
      EXPECT_LT(set[k][b], pairs) << "field " << k << " bit " << b;
    }
  }
}

// Grid faces make corners on the other's plane, coplanar faces and faces
// meeting at an edge common; lines and points have a zero normal and zero
// vectors across their edges.
TEST(NearFeaturesBatchTest, GridAndDegenerateFacesGiveTheOracleAnswers) {
  std::mt19937 rng(42);
  for (int round = 0; round < 200; ++round) {
    const testing::GridPairs grid = testing::GridAndDegeneratePairs(rng);
    for (const double tol : {0.01, 0.0}) ExpectOracleAnswers(grid.a, grid.b, tol, 2 * tol);
  }
}

// A moving face with a NaN coordinate, in each corner in turn, or an
// infinite one: an edge of the floor is beside it only when every corner
// is clearly on one side (a NaN distance is on neither), wherever the NaN
// is, as the definition says. The other two corners lie far across the
// floor's edges, so the NaN decides; the lanes once folded the distances
// with std::min's order, which kept a NaN only in the first corner.
TEST(NearFeaturesBatchTest, NonFiniteCornersGiveTheDefinitionsAnswers) {
  const Triangle3d floor = {Vector3d(0, 0, 0), Vector3d(10, 0, 0), Vector3d(0, 10, 0)};
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<Triangle3d> moving;
  for (const double bad : {nan, inf, -inf}) {
    for (int corner = 0; corner < 3; ++corner) {
      Triangle3d m = {Vector3d(-5, -5, 0), Vector3d(-6, -5, 0), Vector3d(-5, -6, 0.001)};
      m[corner].y() = bad;
      moving.push_back(m);
    }
  }
  const std::vector<NearFeatures> answers = ExpectOracleAnswers(moving, {floor}, 0.01, 0.02);
  for (int corner = 0; corner < 3; ++corner) {
    // Floor edges 0 (y = 0) and 2 (x = 0): the NaN corner's distance across
    // edge 0 is NaN (across edge 2 it is -5 or -6, beside with the others).
    EXPECT_EQ(answers[corner].fixed_edges & 1, 1) << "NaN in corner " << corner;
  }
}

// A fixed face's record: unit normal and the unit vectors across its edges
// into the face, hand-computed for a right triangle; zero for a line.
TEST(NearFeaturesBatchTest, AFixedFaceHasItsNormalAndTheVectorsAcrossItsEdges) {
  const FixedFaceEdges f({Vector3d(0, 0, 0), Vector3d(2, 0, 0), Vector3d(0, 2, 0)});
  EXPECT_EQ(f.unit_normal, Vector3d(0, 0, 1));
  EXPECT_EQ(f.across[0], Vector3d(0, 1, 0));
  EXPECT_EQ(f.across[2], Vector3d(1, 0, 0));
  EXPECT_NEAR((f.across[1] - Vector3d(-1, -1, 0) / std::sqrt(2.0)).norm(), 0, 1e-15);
  EXPECT_EQ(f.edges.lo[1], Vector3d(0, 0, 0));
  EXPECT_EQ(f.edges.hi[1], Vector3d(2, 2, 0));
  const FixedFaceEdges line({Vector3d(0, 0, 0), Vector3d(1, 1, 1), Vector3d(2, 2, 2)});
  EXPECT_EQ(line.unit_normal, Vector3d::Zero());
  for (const Vector3d& a : line.across) EXPECT_EQ(a, Vector3d::Zero());
}

// Hand-placed pairs on a large floor face (corners (0, 0), (10, 0), (0,
// 10)), tolerance 0.01: a small face lying on it far inside has its
// corners on the plane and nothing of the floor near; one straddling the
// floor's hypotenuse has that edge near; one around the floor's corner at
// the origin holds it in its box; one hovering above has no corner near.
TEST(NearFeaturesBatchTest, HandPlacedFacesOnAFloor) {
  const Triangle3d floor = {Vector3d(0, 0, 0), Vector3d(10, 0, 0), Vector3d(0, 10, 0)};
  const std::vector<Triangle3d> moving = {
      {Vector3d(2, 2, 0), Vector3d(2.5, 2, 0), Vector3d(2, 2.5, 0.005)},      // inside, lying
      {Vector3d(4.8, 4.8, 0), Vector3d(5.3, 4.8, 0), Vector3d(4.8, 5.3, 0)},  // over x + y = 10
      {Vector3d(-0.2, -0.2, 0), Vector3d(0.3, -0.2, 0), Vector3d(-0.2, 0.3, 0.5)},  // the origin
      {Vector3d(2, 2, 1), Vector3d(2.5, 2, 1), Vector3d(2, 2.5, 1)}};               // above
  const std::vector<Triangle3d> fixed(moving.size(), floor);
  const std::vector<NearFeatures> got = ExpectOracleAnswers(moving, fixed, 0.01, 0.02);
  EXPECT_EQ(Bits(got[0]), Bits({.moving_corners = 7, .moving_edges = 7}));
  EXPECT_EQ(got[1].fixed_edges, 2) << Bits(got[1]);  // the hypotenuse, edge 1
  EXPECT_EQ(got[1].fixed_corners, 0);
  EXPECT_EQ(got[2].fixed_corners, 1) << Bits(got[2]);
  EXPECT_EQ(got[2].fixed_edges, 5) << Bits(got[2]);  // edges 0 and 2 meet at the origin
  EXPECT_EQ(got[2].moving_corners, 3);
  EXPECT_EQ(Bits(got[3]), Bits({}));
}

}  // namespace
}  // namespace hs

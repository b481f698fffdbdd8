#include "common/collision/plane_bounds_batch.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "hwy/targets.h"
#include "sample_triangles.h"

namespace hs {
namespace {

using testing::RandomTriangle;

constexpr double kInf = std::numeric_limits<double>::infinity();

// The same bits, so that -0 and +0 and NaNs are told apart.
bool SameBits(double x, double y) { return std::memcmp(&x, &y, sizeof x) == 0; }

// Checks the batch against the scalar bounds, pair by pair, bit for bit.
void ExpectScalarBoundsOnTheChosenTarget(const std::vector<Triangle3d>& a,
                                         const std::vector<Triangle3d>& b,
                                         const Vector3d& direction, double margin,
                                         Interval within) {
  // The batch reads the corners where the triangles keep them.
  std::vector<TriangleCorners> corners_a, corners_b;
  for (size_t i = 0; i < b.size(); ++i) {
    corners_a.push_back({&a[i][0], &a[i][1], &a[i][2]});
    corners_b.push_back({&b[i][0], &b[i][1], &b[i][2]});
  }
  std::vector<SweptIntervals> out(b.size());
  SweptPlaneBoundsBatch(corners_a, corners_b, direction, margin, within, out);
  for (size_t i = 0; i < b.size(); ++i) {
    const SweptIntervals scalar = SweptPlaneBounds(a[i], b[i], direction, margin, within);
    EXPECT_TRUE(SameBits(out[i].exact.lo, scalar.exact.lo) &&
                SameBits(out[i].exact.hi, scalar.exact.hi) &&
                SameBits(out[i].within_margin.lo, scalar.within_margin.lo) &&
                SameBits(out[i].within_margin.hi, scalar.within_margin.hi))
        << "pair " << i << " of " << b.size() << ": batch [" << out[i].exact.lo << ", "
        << out[i].exact.hi << "] / [" << out[i].within_margin.lo << ", " << out[i].within_margin.hi
        << "], scalar [" << scalar.exact.lo << ", " << scalar.exact.hi << "] / ["
        << scalar.within_margin.lo << ", " << scalar.within_margin.hi << "]";
  }
}

// Checks the batch against the scalar bounds, face by face, bit for bit,
// on every SIMD target built in that this machine runs (SSE2 to AVX2 or
// AVX-512 on x86-64).
void ExpectScalarBounds(const std::vector<Triangle3d>& a, const std::vector<Triangle3d>& b,
                        const Vector3d& direction, double margin, Interval within) {
  for (const int64_t target : hwy::SupportedAndGeneratedTargets()) {
    hwy::SetSupportedTargetsForTest(target);
    SCOPED_TRACE(hwy::TargetName(target));
    ExpectScalarBoundsOnTheChosenTarget(a, b, direction, margin, within);
  }
  hwy::SetSupportedTargetsForTest(0);
}

// Random pairs of nearby faces, every batch size from 1 to 19 (so that
// every short last batch of every lane count is met), some pairs sharing
// their first face as a sweep's runs do, swept along random directions,
// at tiny, unit and huge scales.
TEST(PlaneBoundsBatchTest, RandomFacesGiveTheScalarBoundsBitForBit) {
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> u(-1, 1);
  for (const double scale : {1e-6, 1.0, 1e4}) {
    for (size_t n = 1; n <= 19; ++n) {
      std::vector<Triangle3d> a, b;
      for (size_t i = 0; i < n; ++i) {
        a.push_back(i % 3 == 2 ? a.back() : RandomTriangle(rng, scale, Vector3d::Zero()));
        b.push_back(RandomTriangle(rng, scale, 0.8 * scale * Vector3d(u(rng), u(rng), u(rng))));
      }
      const Vector3d direction = scale * Vector3d(u(rng), u(rng), u(rng));
      ExpectScalarBounds(a, b, direction, 1e-3 * scale, {0, kInf});
      ExpectScalarBounds(a, b, direction, 0, {-kInf, kInf});
    }
  }
}

// Grid corners make the scalar code's branches common: faces parallel to
// the motion (s = 0), coplanar and touching faces, empty cuts after the
// first axis; degenerate faces (a line, a point) have no usable normal.
TEST(PlaneBoundsBatchTest, GridAndDegenerateFacesGiveTheScalarBounds) {
  std::mt19937 rng(22);
  std::uniform_int_distribution<int> c(-2, 2);
  for (int round = 0; round < 400; ++round) {
    const auto [a, b] = testing::GridAndDegeneratePairs(rng);
    const Vector3d direction(c(rng), c(rng), c(rng));
    ExpectScalarBounds(a, b, direction, 0.01, {0, kInf});
    ExpectScalarBounds(a, b, direction, 0, {0, kInf});
    ExpectScalarBounds(a, b, direction, 0.01, {0.5, 0.25});  // empty to begin with
  }
}

// Non-finite corners give what the scalar code gives (NaN bounds, which
// the sweep then treats as it treats the scalar ones).
TEST(PlaneBoundsBatchTest, NonFiniteCornersGiveTheScalarBounds) {
  const Triangle3d a = {Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0, 1, 0)};
  Triangle3d nan_face = {Vector3d(0, 0, 1), Vector3d(1, 0, 1), Vector3d(0, 1, 1)};
  nan_face[1].x() = std::nan("");
  Triangle3d huge = nan_face;
  huge[1].x() = kInf;
  const Triangle3d fine = {Vector3d(0, 0, 1), Vector3d(1, 0, 1), Vector3d(0, 1, 1)};
  ExpectScalarBounds({a, a, a, nan_face, a}, {nan_face, fine, huge, fine, fine}, Vector3d(0, 0, -1),
                     0.01, {0, kInf});
}

// The batch runs on more than one target here (at least SSE2 and the
// scalar emulation), so that the checks above compare several lane widths.
TEST(PlaneBoundsBatchTest, SeveralTargetsAreChecked) {
  EXPECT_GE(hwy::SupportedAndGeneratedTargets().size(), 2u);
}

}  // namespace
}  // namespace hs

#include "common/collision/face_test_batch.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "common/collision/placed_faces.h"
#include "hwy/targets.h"
#include "sample_triangles.h"

namespace hs {
namespace {

using Answer = QuickTriangleTest::Answer;

bool SameBits(double x, double y) { return std::memcmp(&x, &y, sizeof x) == 0; }

// What a coherent query does with a pair the quick test answers (without
// the edge cross): takes its answer, the hint's edge pair as it was, the
// gap it gives (0 for a meeting) and lever 0. The full test must say the
// same, whatever edge pair the hint held; for an edge cross, which a static
// query takes, its answer.
void ExpectTheFullTestAgrees(const PlacedFace& a, const PlacedFace& b, double margin,
                             const QuickTriangleTest& quick) {
  if (quick.answer == Answer::kUnknown) return;
  const bool edges = quick.answer == Answer::kEdgesApart;
  EXPECT_EQ(quick.edge_pair >= 0 && quick.edge_pair < 9, edges) << int{quick.edge_pair};
  EXPECT_EQ(TrianglesIntersect(a.triangle, a.normal, b.triangle, b.normal, margin),
            quick.answer == Answer::kMeet);
  if (edges) return;
  for (int edge_pair = -1; edge_pair < 9; ++edge_pair) {
    PairHint hint{.edge_pair = edge_pair, .gap_m = 7, .lever_m = 7};
    EXPECT_EQ(TrianglesIntersect(a.triangle, a.normal, b.triangle, b.normal, margin, hint),
              quick.answer == Answer::kMeet);
    EXPECT_EQ(hint.edge_pair, edge_pair);
    EXPECT_TRUE(SameBits(hint.gap_m, quick.gap_m)) << hint.gap_m << " against " << quick.gap_m;
    EXPECT_EQ(hint.lever_m, 0);
  }
}

using Answers = std::array<int, 4>;  // how many pairs got each answer

// Checks the batch against the scalar test, pair by pair and bit for bit,
// on every SIMD target built in that this machine runs (SSE2 to AVX2 or
// AVX-512 on x86-64), with and without the edge cross, and the plane
// tests alone (FacePlanesApartBatch) against its kApart; returns how many
// pairs each answer got with the edge cross.
Answers ExpectScalarAnswers(const std::vector<PlacedFace>& a, const std::vector<PlacedFace>& b,
                            double margin) {
  std::vector<TrianglePair> pairs;  // pair i: a[i] and b[i]
  for (size_t i = 0; i < b.size(); ++i) pairs.push_back({static_cast<int>(i), static_cast<int>(i)});
  Answers answers = {0, 0, 0, 0};
  for (const bool edge_cross : {false, true}) {
    SCOPED_TRACE(edge_cross ? "with the edge cross" : "without the edge cross");
    std::vector<QuickTriangleTest> scalar;
    for (size_t i = 0; i < b.size(); ++i) {
      scalar.push_back(QuickTrianglesTest(a[i].triangle, a[i].normal, b[i].triangle, b[i].normal,
                                          margin, edge_cross));
      if (edge_cross) ++answers[static_cast<int>(scalar.back().answer)];
      EXPECT_TRUE(edge_cross || scalar.back().answer != Answer::kEdgesApart);
      ExpectTheFullTestAgrees(a[i], b[i], margin, scalar.back());
    }
    for (const int64_t target : hwy::SupportedAndGeneratedTargets()) {
      hwy::SetSupportedTargetsForTest(target);
      SCOPED_TRACE(hwy::TargetName(target));
      std::vector<QuickTriangleTest> out(b.size(), {Answer::kUnknown, 5, 7});
      QuickTrianglesTestBatch(a.data(), b.data(), pairs, margin, edge_cross, out);
      for (size_t i = 0; i < b.size(); ++i) {
        EXPECT_TRUE(out[i].answer == scalar[i].answer && out[i].edge_pair == scalar[i].edge_pair &&
                    SameBits(out[i].gap_m, scalar[i].gap_m))
            << "pair " << i << " of " << b.size() << ": batch " << static_cast<int>(out[i].answer)
            << ", " << int{out[i].edge_pair} << ", " << out[i].gap_m << "; scalar "
            << static_cast<int>(scalar[i].answer) << ", " << int{scalar[i].edge_pair} << ", "
            << scalar[i].gap_m;
      }
      // The plane tests alone: the quick test's kApart, and only it.
      std::vector<uint8_t> apart(b.size(), 7);
      FacePlanesApartBatch(a.data(), b.data(), pairs, margin, apart);
      for (size_t i = 0; i < b.size(); ++i) {
        EXPECT_EQ(apart[i], scalar[i].answer == Answer::kApart ? 1 : 0)
            << "pair " << i << " of " << b.size() << ": planes apart";
      }
    }
    hwy::SetSupportedTargetsForTest(0);
  }
  return answers;
}

PlacedFace RandomFace(std::mt19937& rng, double scale, const Vector3d& offset) {
  return PlaceFace(testing::RandomTriangle(rng, scale, offset));
}

// GridAndDegeneratePairs, each side's faces placed.
std::pair<std::vector<PlacedFace>, std::vector<PlacedFace>> PlacedGridPairs(std::mt19937& rng) {
  const testing::GridPairs grid = testing::GridAndDegeneratePairs(rng);
  std::vector<PlacedFace> a, b;
  for (const Triangle3d& t : grid.a) a.push_back(PlaceFace(t));
  for (const Triangle3d& t : grid.b) b.push_back(PlaceFace(t));
  return {a, b};
}

// Random pairs of nearby faces (each answer common), every batch size
// from 1 to 19 (every short last batch of every lane count) and sizes
// beyond the batch's stretch of 64 pairs, some sharing their first face
// as a region's candidates do, at tiny, unit and huge scales, with and
// without a margin.
TEST(FaceTestBatchTest, RandomFacesGiveTheScalarAnswer) {
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<size_t> sizes = {63, 64, 65, 150};
  for (size_t n = 1; n <= 19; ++n) sizes.push_back(n);
  Answers answers = {0, 0, 0, 0};
  for (const double scale : {1e-6, 1.0, 1e4}) {
    for (const size_t n : sizes) {
      std::vector<PlacedFace> a, b;
      for (size_t i = 0; i < n; ++i) {
        a.push_back(i % 3 == 2 ? a.back() : RandomFace(rng, scale, Vector3d::Zero()));
        const double apart = i % 2 == 0 ? 0.3 : 1.5;  // most cross, or most do not
        b.push_back(RandomFace(rng, scale, apart * scale * Vector3d(u(rng), u(rng), u(rng))));
      }
      for (const double margin : {1e-3 * scale, 0.0}) {
        const Answers got = ExpectScalarAnswers(a, b, margin);
        for (int k = 0; k < 4; ++k) answers[k] += got[k];
      }
    }
  }
  // Each answer but kUnknown at least a twentieth of the 3,192 pairs (the
  // full test is left few random pairs: the grid pairs below give it
  // more).
  for (int k = 1; k < 4; ++k) EXPECT_GT(answers[k], 159) << "answer " << k;
}

// Grid corners make the scalar test's refusals common: coplanar faces,
// corners on the other's plane, faces that touch at an edge or a corner;
// degenerate faces (a line, a point) have no usable normal.
TEST(FaceTestBatchTest, GridAndDegenerateFacesGiveTheScalarAnswer) {
  std::mt19937 rng(32);
  Answers answers = {0, 0, 0, 0};
  for (int round = 0; round < 300; ++round) {
    const auto [a, b] = PlacedGridPairs(rng);
    for (const double margin : {0.01, 0.0}) {
      const Answers got = ExpectScalarAnswers(a, b, margin);
      for (int k = 0; k < 4; ++k) answers[k] += got[k];
    }
  }
  for (int k = 0; k < 4; ++k) EXPECT_GT(answers[k], 0) << "answer " << k;
}

// Non-finite corners get no answer that the scalar test does not give
// (the full test then answers for them).
TEST(FaceTestBatchTest, NonFiniteCornersGiveTheScalarAnswer) {
  const PlacedFace a = PlaceFace({Vector3d(-1, -1, 0), Vector3d(2, -1, 0), Vector3d(-1, 2, 0)});
  const PlacedFace crossing =
      PlaceFace({Vector3d(0, 0, -1), Vector3d(0.5, 0, 1), Vector3d(0, 0.5, 1)});
  const PlacedFace above = PlaceFace({Vector3d(0, 0, 1), Vector3d(0.5, 0, 1), Vector3d(0, 0.5, 2)});
  Triangle3d nan_corner = crossing.triangle;
  nan_corner[1].x() = std::nan("");
  Triangle3d infinite = above.triangle;
  infinite[2].z() = std::numeric_limits<double>::infinity();
  const Answers answers = ExpectScalarAnswers(
      {a, a, a, a, a}, {crossing, PlaceFace(nan_corner), PlaceFace(infinite), above, crossing},
      0.01);
  EXPECT_EQ(answers[static_cast<int>(Answer::kMeet)], 2);
  EXPECT_GE(answers[static_cast<int>(Answer::kApart)], 1);
}

// A face standing on another's plane within the margin, beside its
// hypotenuse, does not straddle that plane, so there is no crossing to
// compare: an edge cross keeps them apart (its upright edge against the
// hypotenuse, the hypotenuse's outward normal), found by the batch as by
// the scalar test and agreed by the full test; without the edge cross the
// full test decides.
TEST(FaceTestBatchTest, AFaceStandingBesideAnotherIsKeptApartByAnEdgeCross) {
  const PlacedFace floor = PlaceFace({Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0, 1, 0)});
  std::vector<PlacedFace> a, b;
  for (int k = 0; k < 9; ++k) {
    const double x = 0.6 + 0.05 * k, lift = 0.002 + 0.0005 * k;
    a.push_back(PlaceFace(
        {Vector3d(x, 0.8, lift), Vector3d(x + 0.1, 0.8, lift), Vector3d(x, 0.8, lift + 0.3)}));
    b.push_back(floor);
  }
  const double margin = 0.01;
  const Answers answers = ExpectScalarAnswers(a, b, margin);
  EXPECT_EQ(answers[static_cast<int>(Answer::kEdgesApart)], 9);
  for (const PlacedFace& face : a) {
    EXPECT_EQ(QuickTrianglesTest(face.triangle, face.normal, floor.triangle, floor.normal, margin,
                                 /*edge_cross=*/false)
                  .answer,
              Answer::kUnknown);
    EXPECT_FALSE(
        TrianglesIntersect(face.triangle, face.normal, floor.triangle, floor.normal, margin));
  }
}

// Checks HintedEdgeCrossBatch against EdgeCrossSeparates, bit for bit,
// for every pair (a[i], b[i]) and each of the nine edge pairs as its hint,
// on every SIMD target built in that this machine runs; returns how many
// (pair, hint) it kept apart and how many of those with a lever.
std::pair<int, int> ExpectScalarEdgeCrosses(const std::vector<PlacedFace>& a,
                                            const std::vector<PlacedFace>& b, double margin) {
  std::vector<TrianglePair> pairs;
  std::vector<PairHint> scalar;
  std::vector<bool> scalar_apart;
  for (size_t i = 0; i < b.size(); ++i) {
    for (int k = 0; k < 9; ++k) {
      pairs.push_back({static_cast<int>(i), static_cast<int>(i)});
      PairHint hint{.edge_pair = k, .gap_m = 7, .lever_m = 7};
      scalar_apart.push_back(
          EdgeCrossSeparates(a[i].triangle, b[i].triangle, k / 3, k % 3, margin, hint));
      scalar.push_back(hint);
    }
  }
  for (const int64_t target : hwy::SupportedAndGeneratedTargets()) {
    hwy::SetSupportedTargetsForTest(target);
    SCOPED_TRACE(hwy::TargetName(target));
    std::vector<PairHint> hints;
    for (size_t n = 0; n < pairs.size(); ++n) {
      hints.push_back({.edge_pair = static_cast<int>(n % 9), .gap_m = 7, .lever_m = 7});
    }
    std::vector<uint8_t> separated(pairs.size(), 5);
    HintedEdgeCrossBatch(a.data(), b.data(), pairs, margin, hints, separated);
    for (size_t n = 0; n < pairs.size(); ++n) {
      EXPECT_TRUE(separated[n] == scalar_apart[n] && hints[n].edge_pair == scalar[n].edge_pair &&
                  SameBits(hints[n].gap_m, scalar[n].gap_m) &&
                  SameBits(hints[n].lever_m, scalar[n].lever_m))
          << "pair " << n / 9 << " edge pair " << n % 9 << ": batch " << int{separated[n]} << ", "
          << hints[n].gap_m << ", " << hints[n].lever_m << "; scalar " << scalar_apart[n] << ", "
          << scalar[n].gap_m << ", " << scalar[n].lever_m;
    }
  }
  hwy::SetSupportedTargetsForTest(0);
  int apart = 0, with_lever = 0;
  for (size_t n = 0; n < pairs.size(); ++n) {
    apart += scalar_apart[n];
    with_lever += scalar[n].lever_m > 0;
  }
  return {apart, with_lever};
}

// Random nearby faces at tiny, unit and huge scales, every batch size
// from 1 to 19 faces (9 to 171 pairs), and grid faces with degenerate
// ones (parallel edges, a line, a point: unusable axes), with and without
// a margin: the hinted edge cross and its gap and lever are the scalar's.
TEST(FaceTestBatchTest, HintedEdgeCrossesGiveTheScalarAnswer) {
  std::mt19937 rng(33);
  std::uniform_real_distribution<double> u(-1, 1);
  int apart = 0, with_lever = 0, total = 0;
  for (const double scale : {1e-6, 1.0, 1e4}) {
    for (size_t n = 1; n <= 19; ++n) {
      std::vector<PlacedFace> a, b;
      for (size_t i = 0; i < n; ++i) {
        a.push_back(RandomFace(rng, scale, Vector3d::Zero()));
        b.push_back(RandomFace(rng, scale, 1.2 * scale * Vector3d(u(rng), u(rng), u(rng))));
      }
      for (const double margin : {1e-3 * scale, 0.0}) {
        const auto [k, l] = ExpectScalarEdgeCrosses(a, b, margin);
        apart += k;
        with_lever += l;
        total += 9 * static_cast<int>(n);
      }
    }
  }
  for (int round = 0; round < 100; ++round) {
    const auto [a, b] = PlacedGridPairs(rng);
    for (const double margin : {0.01, 0.0}) {
      const auto [k, l] = ExpectScalarEdgeCrosses(a, b, margin);
      apart += k;
      with_lever += l;
      total += 9 * static_cast<int>(b.size());
    }
  }
  // Both answers common, and most kept apart with a lever to carry.
  EXPECT_GT(apart, total / 10);
  EXPECT_LT(apart, total - total / 10);
  EXPECT_GT(with_lever, apart / 2);
}

// A pair kept apart by the edge cross of its hint: the full test with that
// hint answers the same, with the batch's gap and lever (what a coherent
// query keeps for the pair).
TEST(FaceTestBatchTest, AHintedEdgeCrossAnswersAsTheFullTest) {
  // An upright face beside a floor's hypotenuse, within the margin of its
  // plane: some edge cross keeps them apart (the full test without a hint
  // says so).
  const PlacedFace floor = PlaceFace({Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0, 1, 0)});
  const PlacedFace upright =
      PlaceFace({Vector3d(0.7, 0.8, 0.003), Vector3d(0.8, 0.8, 0.003), Vector3d(0.7, 0.8, 0.303)});
  const double margin = 0.01;
  ASSERT_FALSE(
      TrianglesIntersect(upright.triangle, upright.normal, floor.triangle, floor.normal, margin));
  int kept_apart = 0;
  for (int k = 0; k < 9; ++k) {
    std::vector<PairHint> hints = {{.edge_pair = k}};
    std::vector<uint8_t> separated(1);
    const std::vector<TrianglePair> pairs = {{0, 0}};
    HintedEdgeCrossBatch(&upright, &floor, pairs, margin, hints, separated);
    if (!separated[0]) continue;
    ++kept_apart;
    PairHint full{.edge_pair = k};
    EXPECT_FALSE(TrianglesIntersect(upright.triangle, upright.normal, floor.triangle, floor.normal,
                                    margin, full));
    EXPECT_EQ(full.edge_pair, k);
    EXPECT_TRUE(SameBits(full.gap_m, hints[0].gap_m)) << full.gap_m << " " << hints[0].gap_m;
    EXPECT_TRUE(SameBits(full.lever_m, hints[0].lever_m))
        << full.lever_m << " " << hints[0].lever_m;
    EXPECT_GT(hints[0].gap_m, 0);
    EXPECT_GT(hints[0].lever_m, 0);
  }
  EXPECT_GT(kept_apart, 0);
}

// The batch runs on more than one target here (at least SSE2 and the
// scalar emulation), so that the checks above compare several lane widths.
TEST(FaceTestBatchTest, SeveralTargetsAreChecked) {
  EXPECT_GE(hwy::SupportedAndGeneratedTargets().size(), 2u);
}

}  // namespace
}  // namespace hs

// libFuzzer target: the batched kernels, which work several face pairs at
// a time in SIMD lanes, against the scalar code whose answers they must
// give bit for bit, on faces made of the input's bytes, on every SIMD
// target this machine runs. The faces' coordinates are the input's doubles
// as they are (NaN, infinities, subnormals, huge), or steps of a small
// grid at a scale the input picks (faces that touch, lie in one plane or
// run parallel; lines and points). The kernels:
//  - QuickTrianglesTestBatch, with and without the edge cross, and
//    FacePlanesApartBatch against QuickTrianglesTest (face_test_batch.h);
//  - HintedEdgeCrossBatch against EdgeCrossSeparates;
//  - SweptPlaneBoundsBatch against SweptPlaneBounds (plane_bounds_batch.h);
//  - NearFeaturesBatch against its definition (near_features_oracle.h);
//  - KeepEdgesWhoseLinesMayMeet against EdgeLinesMayMeet (the tool
//    stage's edge search, edge_pairs_batch.h): the first face's edges as
//    the tool's, each against every edge of the batch's second faces.
// A difference prints the kernel, the target and the pair's faces (the
// locator's tests both answers too) and aborts: libFuzzer keeps the input.
// NaNs count as the same whatever their bits (a kernel and the scalar code
// may carry different payloads); every other double must match to the bit,
// signed zeros included.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <vector>

#include "common/collision/face_test_batch.h"
#include "common/collision/placed_faces.h"
#include "common/collision/plane_bounds_batch.h"
#include "common/collision/triangle_sat.h"
#include "common/contact/near_features_batch.h"
#include "common/sim/edge_pairs_batch.h"
#include "hwy/targets.h"
#include "tests/common/contact/near_features_oracle.h"
#include "tests/fuzz/fuzz_bytes.h"

namespace hs {
namespace {

using fuzz::Bytes;

constexpr double kInf = std::numeric_limits<double>::infinity();

bool Same(double x, double y) {
  return (std::isnan(x) && std::isnan(y)) || std::memcmp(&x, &y, sizeof x) == 0;
}

// Prints the pair's faces, corner by corner to the last digit, and aborts.
[[noreturn]] void Differ(const char* kernel, int64_t target, const Triangle3d& a,
                         const Triangle3d& b, size_t pair) {
  std::fprintf(stderr, "%s on %s: pair %zu differs from the scalar code\n", kernel,
               hwy::TargetName(target), pair);
  for (const Triangle3d* face : {&a, &b}) {
    for (const Vector3d& p : *face)
      std::fprintf(stderr, "  (%.17g, %.17g, %.17g)", p.x(), p.y(), p.z());
    std::fprintf(stderr, "\n");
  }
  std::abort();
}

// A face: the input's doubles, or corners on the grid {-2, ..., 2}^3 at a
// scale from the input, shifted by one of the input's doubles (coordinates
// far from the origin round).
Triangle3d Face(Bytes& in) {
  static constexpr double kScales[] = {1e-9, 1e-3, 1.0, 1e6};
  const bool raw = in.Small(4) == 0;
  const double scale = kScales[in.Small(4)];
  const double offset = in.Small(2) == 0 ? 0.0 : in.Number();
  Triangle3d t;
  for (Vector3d& corner : t) {
    for (int d = 0; d < 3; ++d) corner[d] = raw ? in.Number() : (in.Small(5) - 2) * scale + offset;
  }
  return t;
}

// A margin or tolerance, as a query has one: zero, a grid step at a scale,
// or the input's double if finite and not negative.
double Margin(Bytes& in) {
  static constexpr double kSteps[] = {0.0, 1e-9, 1e-3, 1.0};
  const int pick = in.Small(5);
  if (pick < 4) return kSteps[pick];
  const double x = in.Number();
  return std::isfinite(x) && x >= 0 ? x : 0.0;
}
// Everything the kernels are given, read off the input once.
struct Input {
  std::vector<Triangle3d> a, b;  // pair i: a[i] and b[i]
  std::vector<PlacedFace> placed_a, placed_b;
  std::vector<TrianglePair> pairs;  // {i, i}
  double margin = 0;
  double slack = 0;  // the locator's: twice its tolerance and more (Locator::CornerSlack)
  std::vector<PairHint> hints;  // the edge cross each pair kept apart by last time
  Vector3d direction;           // the sweep's
  Interval within;
  std::vector<TriangleCorners> corners_a, corners_b;
  std::vector<MovingFaceCorners> moving;
  std::vector<FixedFaceEdges> fixed;
  std::vector<FaceRecordPair> records;  // {i, i}
  EdgeMove move{0, 0, 0, 0};            // the tool stage's
  std::vector<WorldEdge> edges;         // every edge of the second faces
  EdgeColumns columns;
  std::vector<int> rows;  // every row of `columns`, last first (a search hands rows in its order)
};

// One to 19 pairs (every short last batch of every lane count), some
// sharing their first face as a region's or a sweep's run of pairs does.
Input Read(Bytes& in) {
  Input input;
  const int n = 1 + in.Small(19);
  for (int i = 0; i < n; ++i) {
    input.a.push_back(i > 0 && in.Small(3) == 0 ? input.a.back() : Face(in));
    input.b.push_back(Face(in));
    input.pairs.push_back({i, i});
    input.records.push_back({i, i});
  }
  for (int i = 0; i < n; ++i) {
    input.placed_a.push_back(PlaceFace(input.a[i]));
    input.placed_b.push_back(PlaceFace(input.b[i]));
    input.corners_a.push_back({&input.a[i][0], &input.a[i][1], &input.a[i][2]});
    input.corners_b.push_back({&input.b[i][0], &input.b[i][1], &input.b[i][2]});
    input.moving.push_back({input.a[i]});
    input.fixed.emplace_back(input.b[i]);
  }
  input.margin = Margin(in);
  input.slack = 2 * input.margin + Margin(in);
  for (int i = 0; i < n; ++i)
    input.hints.push_back({.edge_pair = in.Small(9), .gap_m = 7, .lever_m = 7});
  const double x = in.Number(), y = in.Number(), z = in.Number();
  input.direction = {x, y, z};
  input.within = in.Small(2) == 0 ? Interval{0, kInf} : Interval{-kInf, kInf};
  const double turn = Margin(in), radius = Margin(in), behind = Margin(in);
  input.move = EdgeMove(input.margin, turn, radius, behind);
  for (const Triangle3d& face : input.b) {
    for (int k = 0; k < 3; ++k) {
      input.edges.push_back({face[k], face[(k + 1) % 3], Vector3d::Zero()});
      input.columns.Add(input.edges.back(),
                        (input.edges.back().to - input.edges.back().from).norm());
    }
  }
  for (int row = static_cast<int>(input.edges.size()) - 1; row >= 0; --row)
    input.rows.push_back(row);
  return input;
}

// The scalar code's answers, which every target's kernels must give.
struct Answers {
  std::vector<QuickTriangleTest> quick[2];  // without and with the edge cross
  std::vector<PairHint> hints;
  std::vector<uint8_t> hinted_apart;
  std::vector<SweptIntervals> bounds;
  std::vector<NearFeatures> near;
  std::vector<int> kept[3];  // the rows kept for each edge of the first pair's first face
};

Answers ScalarAnswers(const Input& input) {
  Answers answers;
  const size_t n = input.pairs.size();
  for (const bool edge_cross : {false, true}) {
    for (size_t i = 0; i < n; ++i) {
      const PlacedFace &a = input.placed_a[i], &b = input.placed_b[i];
      answers.quick[edge_cross].push_back(
          QuickTrianglesTest(a.triangle, a.normal, b.triangle, b.normal, input.margin, edge_cross));
    }
  }
  answers.hints = input.hints;
  for (size_t i = 0; i < n; ++i) {
    const int k = input.hints[i].edge_pair;
    answers.hinted_apart.push_back(EdgeCrossSeparates(input.placed_a[i].triangle,
                                                      input.placed_b[i].triangle, k / 3, k % 3,
                                                      input.margin, answers.hints[i]));
    answers.bounds.push_back(
        SweptPlaneBounds(input.a[i], input.b[i], input.direction, input.margin, input.within));
    answers.near.push_back(
        testing::NearFeaturesOracle(input.a[i], input.fixed[i], input.margin, input.slack));
  }
  for (int k = 0; k < 3; ++k) {
    const Vector3d& from = input.a[0][k];
    const Vector3d u = input.a[0][(k + 1) % 3] - from;
    for (const int row : input.rows) {
      const WorldEdge& e = input.edges[row];
      const Vector3d v = e.to - e.from;
      if (EdgeLinesMayMeet(from, u, u.norm(), e.from, v, v.norm(), input.move)) {
        answers.kept[k].push_back(row);
      }
    }
  }
  return answers;
}

void QuickTests(const Input& input, const Answers& answers, int64_t target) {
  const size_t n = input.pairs.size();
  for (const bool edge_cross : {false, true}) {
    std::vector<QuickTriangleTest> out(n);
    QuickTrianglesTestBatch(input.placed_a.data(), input.placed_b.data(), input.pairs, input.margin,
                            edge_cross, out);
    std::vector<uint8_t> apart(n);
    FacePlanesApartBatch(input.placed_a.data(), input.placed_b.data(), input.pairs, input.margin,
                         apart);
    for (size_t i = 0; i < n; ++i) {
      const QuickTriangleTest& scalar = answers.quick[edge_cross][i];
      if (out[i].answer != scalar.answer || out[i].edge_pair != scalar.edge_pair ||
          !Same(out[i].gap_m, scalar.gap_m)) {
        Differ(
            edge_cross ? "QuickTrianglesTestBatch with the edge cross" : "QuickTrianglesTestBatch",
            target, input.a[i], input.b[i], i);
      }
      if ((apart[i] != 0) != (scalar.answer == QuickTriangleTest::Answer::kApart)) {
        Differ("FacePlanesApartBatch", target, input.a[i], input.b[i], i);
      }
    }
  }
}

void HintedEdgeCrosses(const Input& input, const Answers& answers, int64_t target) {
  std::vector<PairHint> hints = input.hints;
  std::vector<uint8_t> separated(hints.size());
  HintedEdgeCrossBatch(input.placed_a.data(), input.placed_b.data(), input.pairs, input.margin,
                       hints, separated);
  for (size_t i = 0; i < hints.size(); ++i) {
    const PairHint& scalar = answers.hints[i];
    if ((separated[i] != 0) != (answers.hinted_apart[i] != 0) ||
        hints[i].edge_pair != scalar.edge_pair || !Same(hints[i].gap_m, scalar.gap_m) ||
        !Same(hints[i].lever_m, scalar.lever_m)) {
      Differ("HintedEdgeCrossBatch", target, input.a[i], input.b[i], i);
    }
  }
}

void PlaneBounds(const Input& input, const Answers& answers, int64_t target) {
  std::vector<SweptIntervals> out(input.pairs.size());
  SweptPlaneBoundsBatch(input.corners_a, input.corners_b, input.direction, input.margin,
                        input.within, out);
  for (size_t i = 0; i < out.size(); ++i) {
    const SweptIntervals& scalar = answers.bounds[i];
    if (!Same(out[i].exact.lo, scalar.exact.lo) || !Same(out[i].exact.hi, scalar.exact.hi) ||
        !Same(out[i].within_margin.lo, scalar.within_margin.lo) ||
        !Same(out[i].within_margin.hi, scalar.within_margin.hi)) {
      Differ("SweptPlaneBoundsBatch", target, input.a[i], input.b[i], i);
    }
  }
}

void NearFeatureTests(const Input& input, const Answers& answers, int64_t target) {
  std::vector<NearFeatures> out(input.records.size());
  NearFeaturesBatch(input.moving.data(), input.fixed.data(), input.records, input.margin,
                    input.slack, out);
  for (size_t i = 0; i < out.size(); ++i) {
    const NearFeatures& scalar = answers.near[i];
    if (!testing::SameNearFeatures(out[i], scalar)) {
      std::fprintf(stderr,
                   "lanes %d %d %d %d, definition %d %d %d %d (moving corners and edges, fixed "
                   "corners and edges)\n",
                   out[i].moving_corners, out[i].moving_edges, out[i].fixed_corners,
                   out[i].fixed_edges, scalar.moving_corners, scalar.moving_edges,
                   scalar.fixed_corners, scalar.fixed_edges);
      Differ("NearFeaturesBatch", target, input.a[i], input.b[i], i);
    }
  }
}

// The first pair's first face as the tool's, each of its edges against
// every edge of the second faces.
void EdgeLines(const Input& input, const Answers& answers, int64_t target) {
  std::vector<int> kept(input.rows.size());
  for (int k = 0; k < 3; ++k) {
    const Vector3d& from = input.a[0][k];
    const Vector3d u = input.a[0][(k + 1) % 3] - from;
    const size_t n = KeepEdgesWhoseLinesMayMeet(from, u, u.norm(), input.columns, input.rows,
                                                input.move, kept.data());
    const std::vector<int>& scalar = answers.kept[k];
    for (size_t i = 0; i < std::min(n, scalar.size()); ++i) {
      if (kept[i] != scalar[i]) {
        const int row = std::min(kept[i], scalar[i]);
        Differ("KeepEdgesWhoseLinesMayMeet", target, input.a[0], input.b[row / 3], row / 3);
      }
    }
    if (n != scalar.size()) Differ("KeepEdgesWhoseLinesMayMeet", target, input.a[0], input.b[0], 0);
  }
}

}  // namespace
}  // namespace hs

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  hs::fuzz::Bytes in(data, size);
  const hs::Input input = hs::Read(in);
  const hs::Answers answers = hs::ScalarAnswers(input);
  for (const int64_t target : hwy::SupportedAndGeneratedTargets()) {
    hwy::SetSupportedTargetsForTest(target);
    hs::QuickTests(input, answers, target);
    hs::HintedEdgeCrosses(input, answers, target);
    hs::PlaneBounds(input, answers, target);
    hs::NearFeatureTests(input, answers, target);
    hs::EdgeLines(input, answers, target);
  }
  hwy::SetSupportedTargetsForTest(0);
  return 0;
}

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

struct Batch {
  std::vector<Triangle3d> a, b;  // pair i: a[i] and b[i]
  std::vector<PlacedFace> placed_a, placed_b;
  std::vector<TrianglePair> pairs;  // {i, i}
};

// One to 19 pairs (every short last batch of every lane count), some
// sharing their first face as a region's or a sweep's run of pairs does.
Batch Pairs(Bytes& in) {
  Batch batch;
  const int n = 1 + in.Small(19);
  for (int i = 0; i < n; ++i) {
    batch.a.push_back(i > 0 && in.Small(3) == 0 ? batch.a.back() : Face(in));
    batch.b.push_back(Face(in));
    batch.placed_a.push_back(PlaceFace(batch.a.back()));
    batch.placed_b.push_back(PlaceFace(batch.b.back()));
    batch.pairs.push_back({i, i});
  }
  return batch;
}

void QuickTests(const Batch& batch, double margin, int64_t target) {
  const size_t n = batch.pairs.size();
  for (const bool edge_cross : {false, true}) {
    std::vector<QuickTriangleTest> out(n);
    QuickTrianglesTestBatch(batch.placed_a.data(), batch.placed_b.data(), batch.pairs, margin,
                            edge_cross, out);
    std::vector<uint8_t> apart(n);
    FacePlanesApartBatch(batch.placed_a.data(), batch.placed_b.data(), batch.pairs, margin, apart);
    for (size_t i = 0; i < n; ++i) {
      const PlacedFace &a = batch.placed_a[i], &b = batch.placed_b[i];
      const QuickTriangleTest scalar =
          QuickTrianglesTest(a.triangle, a.normal, b.triangle, b.normal, margin, edge_cross);
      if (out[i].answer != scalar.answer || out[i].edge_pair != scalar.edge_pair ||
          !Same(out[i].gap_m, scalar.gap_m)) {
        Differ(
            edge_cross ? "QuickTrianglesTestBatch with the edge cross" : "QuickTrianglesTestBatch",
            target, batch.a[i], batch.b[i], i);
      }
      if ((apart[i] != 0) != (scalar.answer == QuickTriangleTest::Answer::kApart)) {
        Differ("FacePlanesApartBatch", target, batch.a[i], batch.b[i], i);
      }
    }
  }
}

void HintedEdgeCrosses(const Batch& batch, Bytes& in, double margin, int64_t target) {
  const size_t n = batch.pairs.size();
  std::vector<PairHint> hints(n);
  for (PairHint& hint : hints) hint = {.edge_pair = in.Small(9), .gap_m = 7, .lever_m = 7};
  std::vector<PairHint> scalar = hints;
  std::vector<uint8_t> separated(n);
  HintedEdgeCrossBatch(batch.placed_a.data(), batch.placed_b.data(), batch.pairs, margin, hints,
                       separated);
  for (size_t i = 0; i < n; ++i) {
    const int k = scalar[i].edge_pair;
    const bool apart = EdgeCrossSeparates(batch.placed_a[i].triangle, batch.placed_b[i].triangle,
                                          k / 3, k % 3, margin, scalar[i]);
    if ((separated[i] != 0) != apart || hints[i].edge_pair != scalar[i].edge_pair ||
        !Same(hints[i].gap_m, scalar[i].gap_m) || !Same(hints[i].lever_m, scalar[i].lever_m)) {
      Differ("HintedEdgeCrossBatch", target, batch.a[i], batch.b[i], i);
    }
  }
}

void PlaneBounds(const Batch& batch, Bytes& in, double margin, int64_t target) {
  const Vector3d direction(in.Number(), in.Number(), in.Number());
  const Interval within = in.Small(2) == 0 ? Interval{0, kInf} : Interval{-kInf, kInf};
  const size_t n = batch.pairs.size();
  std::vector<TriangleCorners> corners_a, corners_b;
  for (size_t i = 0; i < n; ++i) {
    corners_a.push_back({&batch.a[i][0], &batch.a[i][1], &batch.a[i][2]});
    corners_b.push_back({&batch.b[i][0], &batch.b[i][1], &batch.b[i][2]});
  }
  std::vector<SweptIntervals> out(n);
  SweptPlaneBoundsBatch(corners_a, corners_b, direction, margin, within, out);
  for (size_t i = 0; i < n; ++i) {
    const SweptIntervals scalar =
        SweptPlaneBounds(batch.a[i], batch.b[i], direction, margin, within);
    if (!Same(out[i].exact.lo, scalar.exact.lo) || !Same(out[i].exact.hi, scalar.exact.hi) ||
        !Same(out[i].within_margin.lo, scalar.within_margin.lo) ||
        !Same(out[i].within_margin.hi, scalar.within_margin.hi)) {
      Differ("SweptPlaneBoundsBatch", target, batch.a[i], batch.b[i], i);
    }
  }
}

void NearFeatureTests(const Batch& batch, double tolerance, double slack, int64_t target) {
  const size_t n = batch.pairs.size();
  std::vector<MovingFaceCorners> moving;
  std::vector<FixedFaceEdges> fixed;
  std::vector<FaceRecordPair> records;
  for (size_t i = 0; i < n; ++i) {
    moving.push_back({batch.a[i]});
    fixed.emplace_back(batch.b[i]);
    records.push_back({static_cast<int32_t>(i), static_cast<int32_t>(i)});
  }
  std::vector<NearFeatures> out(n);
  NearFeaturesBatch(moving.data(), fixed.data(), records, tolerance, slack, out);
  for (size_t i = 0; i < n; ++i) {
    const NearFeatures scalar = testing::NearFeaturesOracle(batch.a[i], fixed[i], tolerance, slack);
    if (!testing::SameNearFeatures(out[i], scalar)) {
      std::fprintf(stderr,
                   "lanes %d %d %d %d, definition %d %d %d %d (moving corners and edges, fixed "
                   "corners and edges)\n",
                   out[i].moving_corners, out[i].moving_edges, out[i].fixed_corners,
                   out[i].fixed_edges, scalar.moving_corners, scalar.moving_edges,
                   scalar.fixed_corners, scalar.fixed_edges);
      Differ("NearFeaturesBatch", target, batch.a[i], batch.b[i], i);
    }
  }
}

void EdgeLines(const Batch& batch, Bytes& in, double margin, int64_t target) {
  const EdgeMove move(margin, Margin(in), Margin(in), Margin(in));
  EdgeColumns columns;
  std::vector<WorldEdge> edges;
  for (const Triangle3d& face : batch.b) {
    for (int k = 0; k < 3; ++k) {
      edges.push_back({face[k], face[(k + 1) % 3], Vector3d::Zero()});
      columns.Add(edges.back(), (edges.back().to - edges.back().from).norm());
    }
  }
  // Every row, last first (a search hands rows in its own order).
  std::vector<int> candidates;
  for (int row = static_cast<int>(edges.size()) - 1; row >= 0; --row) candidates.push_back(row);
  std::vector<int> kept(candidates.size());
  for (int k = 0; k < 3; ++k) {
    const Vector3d& from = batch.a[0][k];
    const Vector3d u = batch.a[0][(k + 1) % 3] - from;
    const double lu = u.norm();
    const size_t n =
        KeepEdgesWhoseLinesMayMeet(from, u, lu, columns, candidates, move, kept.data());
    size_t scalar = 0;
    for (const int row : candidates) {
      const WorldEdge& e = edges[row];
      const Vector3d v = e.to - e.from;
      if (!EdgeLinesMayMeet(from, u, lu, e.from, v, v.norm(), move)) continue;
      if (scalar >= n || kept[scalar] != row) {
        Differ("KeepEdgesWhoseLinesMayMeet", target, batch.a[0], batch.b[row / 3], row / 3);
      }
      ++scalar;
    }
    if (scalar != n) Differ("KeepEdgesWhoseLinesMayMeet", target, batch.a[0], batch.b[0], 0);
  }
}

}  // namespace
}  // namespace hs

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  hs::fuzz::Bytes in(data, size);
  const hs::Batch batch = hs::Pairs(in);
  const double margin = hs::Margin(in);
  // The locator's slack: twice its tolerance and more (Locator::CornerSlack).
  const double slack = 2 * margin + hs::Margin(in);
  const hs::fuzz::Bytes rest = in;  // each target reads the same hints and direction
  for (const int64_t target : hwy::SupportedAndGeneratedTargets()) {
    hwy::SetSupportedTargetsForTest(target);
    hs::fuzz::Bytes target_in = rest;
    hs::QuickTests(batch, margin, target);
    hs::HintedEdgeCrosses(batch, target_in, margin, target);
    hs::PlaneBounds(batch, target_in, margin, target);
    hs::NearFeatureTests(batch, margin, slack, target);
    hs::EdgeLines(batch, target_in, margin, target);
  }
  hwy::SetSupportedTargetsForTest(0);
  return 0;
}

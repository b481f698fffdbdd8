#include "common/sim/edge_pairs_batch.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "hwy/targets.h"
#include "tests/common/sim/random_edges.h"

namespace hs {
namespace {

using testing_edges::DoublesAround;
using testing_edges::FindFlip;
using testing_edges::RandomEdge;
using testing_edges::RandomUnit;
using testing_edges::Shifted;

// Checks the batch against EdgeLinesMayMeet, edge by edge, for tool edge
// `tool` and the rows `candidates` of `edges`, on every SIMD target built
// in that this machine runs; returns how many the scalar test kept.
size_t ExpectScalarAnswers(const WorldEdge& tool, const std::vector<WorldEdge>& edges,
                           const std::vector<int>& candidates, const EdgeMove& move) {
  EdgeColumns columns;
  for (const WorldEdge& e : edges) columns.Add(e, (e.to - e.from).norm());
  const Vector3d u = tool.to - tool.from;
  const double lu = u.norm();
  std::vector<int> scalar;
  for (const int row : candidates) {
    const WorldEdge& e = edges[row];
    if (EdgeLinesMayMeet(tool.from, u, lu, e.from, e.to - e.from, (e.to - e.from).norm(), move)) {
      scalar.push_back(row);
    }
  }
  for (const int64_t target : hwy::SupportedAndGeneratedTargets()) {
    hwy::SetSupportedTargetsForTest(target);
    SCOPED_TRACE(hwy::TargetName(target));
    std::vector<int> kept(candidates.size(), -1);
    const size_t n =
        KeepEdgesWhoseLinesMayMeet(tool.from, u, lu, columns, candidates, move, kept.data());
    kept.resize(n);
    EXPECT_EQ(kept, scalar);
  }
  hwy::SetSupportedTargetsForTest(0);
  return scalar.size();
}

// Random edges near a tool edge, every batch size from 1 to 19 (every
// short last batch of every lane count), at tiny, unit and huge scales and
// far from the origin, with and without a margin and a turn; the
// candidates are rows in another order than the columns', some left out,
// as a grid gives them.
TEST(EdgePairsBatchTest, RandomEdgesGiveTheScalarAnswers) {
  std::mt19937 rng(41);
  size_t kept = 0, tested = 0;
  for (const double scale : {1e-6, 0.01, 1.0, 1e3}) {
    for (const double offset : {0.0, 100.0}) {
      for (const double margin : {0.0, 0.2}) {
        for (const double turn : {0.0, 0.01}) {
          const EdgeMove move(margin * scale, turn, 0.5 * scale, 1e-8 * scale);
          for (int size = 1; size <= 19; ++size) {
            const Vector3d at = Vector3d::Constant(offset * scale);
            const WorldEdge tool = RandomEdge(rng, scale, at);
            std::vector<WorldEdge> edges;
            std::vector<int> candidates;
            for (int k = 0; k < size + 3; ++k) edges.push_back(RandomEdge(rng, scale, at));
            for (int k = 0; k < size; ++k) candidates.push_back(size + 2 - k);
            kept += ExpectScalarAnswers(tool, edges, candidates, move);
            tested += candidates.size();
          }
        }
      }
    }
  }
  // Both answers are common.
  EXPECT_GT(kept, tested / 10);
  EXPECT_LT(kept, tested * 9 / 10);
}

// Parallel, nearly parallel, zero-length and coincident edges, crossing
// edges at their ends, and non-finite coordinates: the answers the scalar
// test gives, lane by lane, beside ordinary edges in the same batch.
TEST(EdgePairsBatchTest, DegenerateEdgesGiveTheScalarAnswers) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const Vector3d z = Vector3d::UnitZ();
  const WorldEdge tool{{-1, 0, 0.001}, {1, 0, 0.001}, -z};
  const std::vector<WorldEdge> edges = {
      {{0, -1, 0}, {0, 1, 0}, z},                  // crossed
      {{-1, 0, 0}, {1, 0, 0}, z},                  // parallel
      {{-1, 0, 0}, {1, 1e-9, 0}, z},               // nearly parallel
      {{0.5, 0.5, 0}, {0.5, 0.5, 0}, z},           // no length
      {{-1, 0, 0.001}, {1, 0, 0.001}, z},          // the tool edge itself
      {{1, -1, 0}, {1, 1, 0}, z},                  // crossing the tool edge's end
      {{1 + 1e-12, -1, 0}, {1 + 1e-12, 1, 0}, z},  // just past it
      {{1.1, -1, 0}, {1.1, 1, 0}, z},              // past it
      {{0, 1, 0}, {0, 2, 0}, z},                   // the lines cross off this edge
      {{nan, 0, 0}, {0, 1, 0}, z},
      {{0, inf, 0}, {0, 1, 0}, z},
      {{0, -1, 5}, {0, 1, 5}, z},  // far above
  };
  std::vector<int> all;
  for (size_t k = 0; k < edges.size(); ++k) all.push_back(static_cast<int>(k));
  for (const double margin : {0.0, 0.002}) {
    for (const double turn : {0.0, 0.01}) {
      SCOPED_TRACE(testing::Message() << "margin " << margin << " turn " << turn);
      EXPECT_GT(ExpectScalarAnswers(tool, edges, all, EdgeMove(margin, turn, 0.01, 1e-8)), 0u);
    }
  }
}

// Object edges shifted to where the scalar answer flips (found by
// bisection along a random direction), and a few doubles either side of
// it: where an operation done in another order than the scalar's would
// change an answer.
TEST(EdgePairsBatchTest, EdgesWhereTheAnswerFlipsGiveTheScalarAnswers) {
  std::mt19937 rng(43);
  int flips = 0;
  for (const double margin : {0.0, 0.002}) {
    for (const double turn : {0.0, 0.01}) {
      const EdgeMove move(margin, turn, 0.01, 1e-8);
      for (int trial = 0; trial < 40; ++trial) {
        const WorldEdge tool = RandomEdge(rng, 0.01, Vector3d::Zero());
        const WorldEdge object = RandomEdge(rng, 0.01, Vector3d::Zero());
        const Vector3d direction = RandomUnit(rng);
        const Vector3d u = tool.to - tool.from;
        auto keeps = [&](double s) {
          const WorldEdge o = Shifted(object, s, direction);
          return EdgeLinesMayMeet(tool.from, u, u.norm(), o.from, o.to - o.from,
                                  (o.to - o.from).norm(), move);
        };
        double lo, hi;
        if (!FindFlip(keeps, lo, hi)) continue;
        ++flips;
        std::vector<WorldEdge> edges;
        for (const double s : DoublesAround(lo)) edges.push_back(Shifted(object, s, direction));
        std::vector<int> all;
        for (size_t k = 0; k < edges.size(); ++k) all.push_back(static_cast<int>(k));
        const size_t kept = ExpectScalarAnswers(tool, edges, all, move);
        EXPECT_GT(kept, 0u);
        EXPECT_LT(kept, edges.size());
      }
    }
  }
  EXPECT_GT(flips, 40);
}

TEST(EdgePairsBatchTest, NoCandidatesKeepNone) {
  EdgeColumns columns;
  int kept = -1;
  EXPECT_EQ(KeepEdgesWhoseLinesMayMeet(Vector3d::Zero(), Vector3d::UnitX(), 1, columns, {},
                                       EdgeMove(0, 0, 0.01, 0), &kept),
            0u);
  EXPECT_EQ(kept, -1);
}

}  // namespace
}  // namespace hs

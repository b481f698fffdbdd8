#include "common/contact/sweep_method.h"

#include <algorithm>
#include <limits>

#include "common/collision/triangle_pairs.h"
#include "common/contact/contact_features.h"

namespace hs {
namespace {

// A query finds new pairs only while the cover grows; each round adds at
// least one pair, and real scenes settle in two or three rounds.
constexpr int kMaxRounds = 64;

Isometry3d MovedBack(const ContactContext& c, double t) {
  Isometry3d X = c.X_FM;
  X.pretranslate(-t * c.direction_F);
  return X;
}

}  // namespace

ContactSet ReconstructBySweep(const ContactContext& c) {
  const Vector3d& D = c.direction_F;
  // t* = the end of the run of sweep intervals that covers t = 0, where
  // pair (a, b) intersects over the interval of t in which a - t D meets b.
  // Intervals are exact (zero margin); runs may chain across gaps below the
  // tolerance, which count as touching.
  std::vector<TrianglePair> known;  // sorted
  std::vector<Interval> intervals;
  // Returns whether any pair was new.
  auto add_pairs = [&](std::vector<TrianglePair> pairs) {
    std::sort(pairs.begin(), pairs.end());
    const size_t old_size = known.size();
    for (const TrianglePair& pair : pairs) {
      if (std::binary_search(known.begin(), known.begin() + old_size, pair)) continue;
      known.push_back(pair);
      // Sweep intervals are translation-invariant, so take a at t = 0. Only
      // t >= 0 can extend the run from t = 0.
      const Interval interval =
          SweptIntersection(c.MovingTriangle(pair.a), c.FixedTriangle(pair.b), D, 0.0,
                            {0, std::numeric_limits<double>::infinity()});
      if (!interval.empty()) intervals.push_back(interval);
    }
    std::inplace_merge(known.begin(), known.begin() + old_size, known.end());
    return known.size() > old_size;
  };
  add_pairs(c.pairs);

  double t_star = 0;
  std::vector<TrianglePair> at_t_star = c.pairs;
  // Objects that only touch need no reversing, whatever D is: a D along
  // the touching faces would otherwise chain across their whole overlap. A
  // pair penetrates when it overlaps by more than the tolerance along every
  // separating axis at t = 0.
  const bool penetrating = std::any_of(c.pairs.begin(), c.pairs.end(), [&](const TrianglePair& p) {
    return !SweptIntersection(c.MovingTriangle(p.a), c.FixedTriangle(p.b), D, -c.tolerance_m,
                              {0, 0})
                .empty();
  });
  bool settled = !penetrating;
  for (int round = 0; round < kMaxRounds && !settled; ++round) {
    std::sort(intervals.begin(), intervals.end(),
              [](const Interval& x, const Interval& y) { return x.lo < y.lo; });
    const double before = t_star;
    for (const Interval& interval : intervals) {
      if (interval.lo <= t_star + c.tolerance_m && interval.hi > t_star) t_star = interval.hi;
    }
    if (round > 0 && t_star == before) {
      settled = true;
      break;
    }
    at_t_star.clear();
    FindIntersectingTriangles(c.moving_model, MovedBack(c, t_star), c.fixed_model,
                              Isometry3d::Identity(), c.tolerance_m, at_t_star);
    settled = !add_pairs(at_t_star);
  }

  ContactSet set;
  set.colliding = true;
  set.depth_m = t_star;
  set.penetrating = t_star > c.tolerance_m;
  set.direction_W = D;
  set.reversing_vector_W = -t_star * D;
  set.fallback = !settled;
  const LocatedContacts located = LocateContacts(c, MovedBack(c, t_star), at_t_star);
  set.moving = located.moving;
  set.fixed = located.fixed;
  set.points = located.points;
  set.normal_W = located.normal_F;
  return set;
}

}  // namespace hs

#include "common/contact/sweep_method.h"

#include <algorithm>
#include <iterator>
#include <limits>
#include <span>

#include "common/collision/plane_bounds_batch.h"
#include "common/collision/triangle_pairs.h"
#include "common/contact/contact_features.h"
#include "common/contact/placed_vertices.h"
#include "common/core/scratch.h"

namespace hs {
namespace {

// Each round at least doubles the stretch of the motion searched, from at
// least twice the tolerance, so 64 rounds reach 2^65 tolerances (over 1e19
// object sizes); real scenes settle in two or three.
constexpr int kMaxRounds = 64;

Isometry3d MovedBack(const ContactContext& c, double t) {
  Isometry3d X = c.X_FM;
  X.pretranslate(-t * c.direction_F);
  return X;
}

// The face pairs met so far, sorted, each with its sweep intervals along D
// over t >= 0 (units of D, so metres), with M at t = 0: sweep intervals are
// translation-invariant, whatever pose found the pair. Each pair has cheap
// bounds (SweptPlaneBounds) of its exact interval and of its interval
// within the tolerance; the exact one is computed once, and only when its
// bound says it could extend the run: most pairs of a deep contact leave
// the other object's plane well before the run ends.
class KnownPairs {
 public:
  // Takes the current scratch space's storage (one at a time per space),
  // empty.
  explicit KnownPairs(const ContactContext& c)
      : c_(c),
        s_(storage()),
        known_(s_.known),
        pairs_(s_.pairs),
        exact_(s_.exact),
        scratch_(s_.scratch),
        reaching_(s_.reaching) {
    s_.Clear();
    s_.moving_vertices.Reset(c.moving, c.X_FM);
  }
  KnownPairs(const KnownPairs&) = delete;
  KnownPairs& operator=(const KnownPairs&) = delete;

  /// Every pair known, sorted: what later queries need not find again.
  std::span<const TrianglePair> pairs() const { return pairs_; }

  // Adds the pairs not known yet.
  void Add(std::span<const TrianglePair> found) {
    std::vector<TrianglePair>& pairs = s_.sorted;
    pairs.assign(found.begin(), found.end());
    std::sort(pairs.begin(), pairs.end());
    // The new pairs and their faces (M's sorted: one placed per run of its
    // pairs), for their bounds several at a time, written by index: the
    // buffers are only grown, since a shrink would refill them at the
    // next, larger, Add. Only t >= 0 can extend the run from t = 0.
    if (s_.added.size() < pairs.size()) {
      s_.added.resize(pairs.size());
      s_.moving.resize(pairs.size());
      s_.fixed.resize(pairs.size());
      s_.bounds.resize(pairs.size());
    }
    size_t n = 0;
    TriangleCorners placed{};  // of the last pair's face of M
    FaceId moving_face = -1;
    for (const TrianglePair& pair : pairs) {
      if (std::binary_search(pairs_.begin(), pairs_.end(), pair)) continue;
      if (pair.a != moving_face) {
        placed = s_.moving_vertices.Corners(pair.a);
        moving_face = pair.a;
      }
      s_.added[n] = pair;
      s_.moving[n] = placed;
      s_.fixed[n] = c_.FixedCorners(pair.b);
      ++n;
    }
    if (n == 0) return;
    const std::span<SweptIntervals> bounds = std::span(s_.bounds).first(n);
    SweptPlaneBoundsBatch(std::span(s_.moving).first(n), std::span(s_.fixed).first(n),
                          c_.direction_F, c_.tolerance_m, kAhead, bounds);
    const size_t old_size = known_.size();
    for (size_t i = 0; i < n; ++i) {
      known_.push_back({.pair = s_.added[i], .bounds = bounds[i], .computed = false});
    }
    if (old_size == 0) {
      pairs_.assign(s_.added.begin(), s_.added.begin() + static_cast<std::ptrdiff_t>(n));
      return;
    }
    // Merged through a second buffer: std::inplace_merge would allocate one.
    s_.merged.resize(known_.size());
    std::merge(known_.begin(), known_.begin() + static_cast<std::ptrdiff_t>(old_size),
               known_.begin() + static_cast<std::ptrdiff_t>(old_size), known_.end(),
               s_.merged.begin());
    known_.swap(s_.merged);
    pairs_.resize(known_.size());
    for (size_t i = 0; i < known_.size(); ++i) pairs_[i] = known_[i].pair;
  }

  // Extends the run of exact intervals that covers t = 0 from `t_star`:
  // runs chain across gaps below the tolerance, which count as touching.
  // A pair whose bound ends before the run as it stands cannot extend it,
  // nor bridge a gap inside it: the pairs bound to reach furthest are
  // computed first, in batches that double, until none of the rest can.
  // Which of them are computed beyond that does not change the run (one
  // that ends before it cannot extend it), so they are taken from a heap,
  // not sorted: most runs end after a batch or two.
  double ExtendRun(double t_star) {
    double run = Chain(t_star);
    std::vector<KnownPair*>& reaching = reaching_;
    reaching.clear();
    for (KnownPair& k : known_) {
      if (!k.computed && k.bounds.exact.hi > run) reaching.push_back(&k);
    }
    const auto reaches_less = [](const KnownPair* x, const KnownPair* y) {
      return x->bounds.exact.hi < y->bounds.exact.hi;
    };
    std::make_heap(reaching.begin(), reaching.end(), reaches_less);
    for (size_t batch = 8; !reaching.empty() && reaching.front()->bounds.exact.hi > run;
         batch *= 2) {
      for (size_t k = 0; k < batch && !reaching.empty(); ++k) {
        std::pop_heap(reaching.begin(), reaching.end(), reaches_less);
        Compute(*reaching.back());
        reaching.pop_back();
      }
      run = Chain(t_star);
    }
    return run;
  }

  // Every pair within the tolerance of each other at `t`, among others
  // whose bound holds `t` only: locating contacts tests each pair itself,
  // and one that does not touch adds nothing.
  void MayTouchAt(double t, std::vector<TrianglePair>& pairs) const {
    pairs.clear();
    for (const KnownPair& k : known_) {
      if (k.bounds.within_margin.Contains(t)) pairs.push_back(k.pair);
    }
  }

 private:
  static constexpr Interval kAhead{0, std::numeric_limits<double>::infinity()};

  struct KnownPair {
    TrianglePair pair;
    SweptIntervals bounds;  // each holds its interval
    bool computed = false;  // whether its exact interval is (in exact_)
    bool operator<(const KnownPair& other) const { return pair < other.pair; }
  };

  // The run from `t_star` over the exact intervals computed so far.
  double Chain(double t_star) {
    std::vector<Interval>& exact = scratch_;
    exact.clear();
    for (const Interval& interval : exact_) {
      // One that ends by t* cannot extend a run from it.
      if (interval.hi > t_star) exact.push_back(interval);
    }
    std::sort(exact.begin(), exact.end(),
              [](const Interval& x, const Interval& y) { return x.lo < y.lo; });
    for (const Interval& interval : exact) {
      if (interval.lo <= t_star + c_.tolerance_m && interval.hi > t_star) t_star = interval.hi;
    }
    return t_star;
  }

  void Compute(KnownPair& k) {
    const Interval exact = SweptIntersection(
        c_.MovingTriangle(k.pair.a), c_.FixedTriangle(k.pair.b), c_.direction_F, 0.0, kAhead);
    k.computed = true;
    if (!exact.empty()) exact_.push_back(exact);
  }

  // Buffers kept from one query to the next (common/core/scratch.h) so
  // that a steady stream of queries does not allocate.
  struct Storage {
    std::vector<KnownPair> known;
    std::vector<KnownPair> merged;
    std::vector<TrianglePair> pairs;  // known's pairs, for pairs()
    // The non-empty exact intervals computed, in the order computed: Chain
    // reads these, not every known pair (most are never computed).
    std::vector<Interval> exact;
    std::vector<TrianglePair> sorted;
    // The new pairs Add takes, their faces, and their bounds.
    std::vector<TrianglePair> added;
    std::vector<TriangleCorners> moving;
    std::vector<TriangleCorners> fixed;
    std::vector<SweptIntervals> bounds;
    std::vector<Interval> scratch;
    std::vector<KnownPair*> reaching;
    // M's vertices placed at c.X_FM, each once per query.
    PlacedVertices moving_vertices;
    void Clear() {
      known.clear();
      pairs.clear();
      exact.clear();
    }
  };
  static Storage& storage() { return Scratch<Storage>(); }

  const ContactContext& c_;
  Storage& s_;
  std::vector<KnownPair>& known_;
  std::vector<TrianglePair>& pairs_;
  std::vector<Interval>& exact_;
  std::vector<Interval>& scratch_;
  std::vector<KnownPair*>& reaching_;
};

// Whether M and F overlap by more than the tolerance rather than touch.
// Mostly some pair overlaps by more than it along every separating axis.
// When none does, the objects touch, or they are boxes penetrating with
// aligned sides (every pair then meets at an edge of one of the two): M
// moved 2 eps off the touched fixed faces is apart in the first case only.
bool Penetrating(const ContactContext& c) {
  const bool deep_pair = std::any_of(c.pairs.begin(), c.pairs.end(), [&](const TrianglePair& p) {
    return !SweptIntersection(c.MovingTriangle(p.a), c.FixedTriangle(p.b), c.direction_F,
                              -c.tolerance_m, {0, 0})
                .empty();
  });
  if (deep_pair) return true;
  const Vector3d off = c.TouchedFixedNormals();   // out of the touched fixed faces
  if (!(off.squaredNorm() > 1e-24)) return true;  // no way off: do not drop a contact
  Isometry3d X_FM = c.X_FM;
  X_FM.pretranslate(2 * c.tolerance_m * off.normalized());
  return AnyTrianglesMeet(c.moving_model, X_FM, std::nullopt, c.fixed_model, Isometry3d::Identity(),
                          c.tolerance_m);
}

// ReconstructBySweep's pair lists and located contacts.
struct SweepBuffers {
  std::vector<TrianglePair> at_t_star, found_at_t1, swept, merged;
  LocatedContacts located;
};

}  // namespace

void ReconstructBySweep(const ContactContext& c, ContactSetF& set) {
  const Vector3d& D = c.direction_F;
  // t* = the end of the run of sweep intervals that covers t = 0, where
  // pair (a, b) intersects over the interval of t in which a - t D meets b.
  // Intervals are exact (zero margin); runs may chain across gaps below the
  // tolerance, which count as touching.
  KnownPairs known(c);
  known.Add(c.pairs);

  // Objects that only touch need no reversing, whatever D is: a D along
  // the touching faces would otherwise chain across their whole overlap.
  const bool penetrating = Penetrating(c);
  double t_star = 0;
  // Buffers reused from query to query (no allocation once large enough).
  SweepBuffers& buffers = Scratch<SweepBuffers>();
  std::vector<TrianglePair>& at_t_star = buffers.at_t_star;
  std::vector<TrianglePair>& found_at_t1 = buffers.found_at_t1;
  std::vector<TrianglePair>& swept = buffers.swept;
  LocatedContacts& located = buffers.located;
  at_t_star.assign(c.pairs.begin(), c.pairs.end());
  bool settled = !penetrating;
  if (!settled) {
    t_star = known.ExtendRun(t_star);
    const double t1 = t_star;
    // Given a depth where M is expected to be apart, past t1: the first
    // swept stretch below reaches it at once, and brings the pairs at t1.
    const bool hinted = c.depth_hint_m > t1 + 2 * c.tolerance_m;
    found_at_t1.clear();  // new pairs the query at t1 found
    double stretch;
    if (hinted) {
      stretch = c.depth_hint_m - t1;
    } else {
      // A pair that could extend the run past t* meets at t*, so one query
      // there, for the pairs not known yet, usually settles it.
      FindIntersectingTriangles(c.moving_model, MovedBack(c, t1), c.fixed_model,
                                Isometry3d::Identity(), c.tolerance_m, found_at_t1, known.pairs(),
                                c.pair_cache);
      known.Add(found_at_t1);
      t_star = known.ExtendRun(t_star);
      settled = t_star == t1;
      // The first stretch is as long as the run grew at t1: a short sweep
      // meets few faces, and a run that goes on far is reached in a few
      // doublings.
      stretch = std::max(2 * c.tolerance_m, t_star - t1);
    }
    // Faces wholly inside the other object are in no pair until M backs out
    // to them, so a deep contact of a fine mesh would take a query per ring
    // of faces. Swept queries over the next stretch instead, each twice as
    // long as the last: every pair that meets in [t1, covered] is then
    // known, and none outside it can reach a run ending before `covered`.
    double covered = t1;
    for (int round = 0; round < kMaxRounds && !settled; ++round, stretch *= 2) {
      const double reach = std::max(t_star + 2 * c.tolerance_m, covered + stretch);
      swept.clear();
      // Planes only: ExtendRun finds the exact interval of each pair whose
      // bound could extend the run, and those that cannot need none.
      FindSweptTrianglePairs(c.moving_model, MovedBack(c, covered), (reach - covered) * D,
                             c.fixed_model, Isometry3d::Identity(), c.tolerance_m, swept,
                             known.pairs(), SweptFaceTest::kPlanesOnly);
      known.Add(swept);
      covered = reach;
      t_star = known.ExtendRun(t_star);
      settled = t_star + c.tolerance_m <= covered;
    }
    // The pairs that may touch at t*: all known, since [t1, covered] holds
    // t*; those the query at t1 found (t* = t1) stand whatever their
    // bounds' rounding says.
    known.MayTouchAt(t_star, at_t_star);
    if (t_star == t1 && !found_at_t1.empty()) {
      // at_t_star is sorted as the known pairs are, found_at_t1 short: its
      // own sort and a merge, not a sort of both.
      std::sort(found_at_t1.begin(), found_at_t1.end());
      found_at_t1.erase(std::unique(found_at_t1.begin(), found_at_t1.end()), found_at_t1.end());
      buffers.merged.clear();
      std::set_union(at_t_star.begin(), at_t_star.end(), found_at_t1.begin(), found_at_t1.end(),
                     std::back_inserter(buffers.merged));
      at_t_star.swap(buffers.merged);
    }
  }

  set.colliding = true;
  set.depth_m = t_star;
  set.penetrating = t_star > c.tolerance_m;
  set.direction_F = D;
  set.reversing_vector_F = -t_star * D;
  set.fallback = !settled;
  set.singular_case = false;
  set.plane_depths_m.fill(std::numeric_limits<double>::infinity());
  LocateContacts(c, MovedBack(c, t_star), at_t_star, located);
  set.moving = located.moving;
  set.fixed = located.fixed;
  set.points = located.points;
  set.normal_F = located.normal_F;
}

}  // namespace hs

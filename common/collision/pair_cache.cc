#include "common/collision/pair_cache.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <span>

#include "common/collision/fcl_bvh.h"
#include "common/core/check.h"

namespace hs {

void PairCache::Clear() {
  for (Region& region : regions_) {
    region.a = region.b = 0;
    region.candidates.clear();
    region.last_use = 0;
  }
}

void PairCache::Restart(double skin_m) {
  HS_CHECK(skin_m > 0);
  Clear();
  skin_m_ = skin_m;
}

namespace {

// The default skin of a region of models `a` and `b`, metres.
double SkinOf(const CollisionModel::Impl& a, const CollisionModel::Impl& b) {
  return PairCache::kSkinRelative * (a.radius + b.radius);
}

}  // namespace

double PairCache::DefaultSkin(const CollisionModel& a, const CollisionModel& b) {
  return SkinOf(a.impl(), b.impl());
}

int PairCache::regions() const {
  return static_cast<int>(
      std::count_if(regions_.begin(), regions_.end(), [](const Region& r) { return r.a != 0; }));
}

double RelativeTurn(const Isometry3d& X_AB_from, const Isometry3d& X_AB_to) {
  // R_to - R_from = R_from (R - I) with R a turn by some angle a, whose
  // singular values are 2 sin(a/2) twice and 0: its largest is the
  // Frobenius norm over sqrt(2), which the entries give without the
  // cancellation of the angle's cosine.
  return (X_AB_to.linear() - X_AB_from.linear()).norm() / std::sqrt(2.0);
}

namespace {

// B's motion in A's frame between two of its poses, as the bounds below
// take it: the turn (RelativeTurn), and how far A's centre moves in B's
// frame and B's in A's frame.
struct Step {
  double turn = 0;
  double a_centre_m = 0, b_centre_m = 0;

  // RelativeShift.
  double Shift() const { return std::max(a_centre_m, b_centre_m); }
  // RelativeMotionBound: a point p of B moves by (R_to - R_from) (p - c) +
  // (X_to c - X_from c), c its model's centre, |p - c| <= radius. A's
  // points in B's frame alike, under the inverses.
  double MotionBound(const CollisionModel::Impl& a, const CollisionModel::Impl& b) const {
    return std::max(turn * a.radius + a_centre_m, turn * b.radius + b_centre_m);
  }
};

Step StepBetween(const CollisionModel::Impl& a, const CollisionModel::Impl& b,
                 const Isometry3d& X_AB_from, const Isometry3d& X_AB_to) {
  return {.turn = RelativeTurn(X_AB_from, X_AB_to),
          .a_centre_m = (X_AB_to.inverse() * a.centre - X_AB_from.inverse() * a.centre).norm(),
          .b_centre_m = (X_AB_to * b.centre - X_AB_from * b.centre).norm()};
}

}  // namespace

double RelativeShift(const CollisionModel::Impl& a, const CollisionModel::Impl& b,
                     const Isometry3d& X_AB_from, const Isometry3d& X_AB_to) {
  return StepBetween(a, b, X_AB_from, X_AB_to).Shift();
}

double RelativeMotionBound(const CollisionModel::Impl& a, const CollisionModel::Impl& b,
                           const Isometry3d& X_AB_from, const Isometry3d& X_AB_to) {
  return StepBetween(a, b, X_AB_from, X_AB_to).MotionBound(a, b);
}

double PairCache::Rounding(const CollisionModel::Impl& a, const CollisionModel::Impl& b,
                           const Isometry3d& X_AB) {
  const double coordinates =
      a.centre.norm() + a.radius + b.centre.norm() + b.radius + X_AB.translation().norm();
  return kRoundingRelative * coordinates;
}

bool PairCache::Worthwhile(const CollisionModel::Impl& a, const CollisionModel::Impl& b,
                           const Isometry3d& X_AB) {
  const double radii = a.radius + b.radius;
  return SkinOf(a, b) + Rounding(a, b, X_AB) < radii;
}

namespace {

// Whether `region` was built for models `a` and `b` at their current
// geometry and for `margin_m`.
bool BuiltFor(const PairCache::Region& region, const CollisionModel::Impl& a,
              const CollisionModel::Impl& b, double margin_m) {
  return region.a == a.id && region.b == b.id && region.version_a == a.geometry_version &&
         region.version_b == b.geometry_version && region.margin_m == margin_m;
}

// B's pose `steps` steps on from X_AB at the step from X_AB_from to X_AB:
// the step's turn and shift each taken `steps` times, close to where a
// steady motion goes.
Isometry3d StepsOn(const Isometry3d& X_AB_from, const Isometry3d& X_AB, double steps) {
  const Isometry3d step = X_AB_from.inverse() * X_AB;
  Eigen::AngleAxisd turn(step.linear());
  turn.angle() *= steps;
  Isometry3d ahead = X_AB;
  ahead.translate(steps * step.translation());
  ahead.rotate(turn);
  return ahead;
}

// Where to build a region of skin `skin_m` for a query at X_AB: ahead of
// it along the motion of the run of queries it has just left (the run, of
// any region, whose last query lies nearest, a small step away), so that a
// steady motion crosses the skin's whole width before it leaves, twice
// what it crosses from a region built at its own pose: half the builds. At
// X_AB itself when no run's last query is a small step away (a jump, or
// the first query), or the motion does not go on as it went.
Isometry3d BuildPose(std::span<const PairCache::Region> regions, const CollisionModel::Impl& a,
                     const CollisionModel::Impl& b, double margin_m, const Isometry3d& X_AB,
                     double skin_m) {
  const PairCache::Stream* last = nullptr;
  double step = std::numeric_limits<double>::infinity();
  for (const PairCache::Region& region : regions) {
    if (!BuiltFor(region, a, b, margin_m)) continue;
    for (const PairCache::Stream& stream : region.streams) {
      if (!stream.used) continue;
      const double from_last = RelativeMotionBound(a, b, stream.X_AB_last, X_AB);
      if (from_last < step) {
        step = from_last;
        last = &stream;
      }
    }
  }
  if (!last || !(step > 0) || !(step < skin_m / 4)) return X_AB;
  const Isometry3d ahead = StepsOn(last->X_AB_last, X_AB, std::floor(0.8 * skin_m / step));
  return RelativeMotionBound(a, b, ahead, X_AB) <= 0.9 * skin_m ? ahead : X_AB;
}

// Moves `region` on to a query at X_AB: the query joins the run whose last
// query lies nearest, or starts a free one unless that last query is at
// X_AB itself, and each run's travel to it is taken. Each run's step to
// X_AB is computed once, for both.
void MoveOn(PairCache::Region& region, const CollisionModel::Impl& a, const CollisionModel::Impl& b,
            const Isometry3d& X_AB) {
  // From each run's last query; zero for a run this query starts.
  std::array<Step, PairCache::kStreams> steps;
  int joined = 0, free = -1;
  double nearest_m = std::numeric_limits<double>::infinity();
  for (int s = 0; s < PairCache::kStreams; ++s) {
    const PairCache::Stream& stream = region.streams[s];
    if (!stream.used) {
      if (free < 0) free = s;
      continue;
    }
    steps[s] = StepBetween(a, b, stream.X_AB_last, X_AB);
    const double from_last = steps[s].MotionBound(a, b);
    if (from_last < nearest_m) {
      nearest_m = from_last;
      joined = s;
    }
  }
  if (free >= 0 && nearest_m != 0) {
    joined = free;
    region.streams[joined] = {.used = true, .X_AB_last = X_AB, .travel = {}};
  }
  for (int s = 0; s < PairCache::kStreams; ++s) {
    const PairCache::Stream& stream = region.streams[s];
    PairCache::Travel& to_query = region.to_query[s];
    to_query = stream.travel;
    if (!stream.used) continue;
    to_query.shifted_m += steps[s].Shift();
    to_query.turned += steps[s].turn;
  }
  region.streams[joined].travel = region.to_query[joined];
  region.streams[joined].X_AB_last = X_AB;
  region.stream = joined;
}

}  // namespace

PairCache::Region* PairCache::Find(const CollisionModel::Impl& a, const CollisionModel::Impl& b,
                                   double margin_m, const Isometry3d& X_AB) {
  for (Region& region : regions_) {
    if (!BuiltFor(region, a, b, margin_m)) continue;
    if (RelativeMotionBound(a, b, region.X_AB, X_AB) <= region.skin_m) {
      MoveOn(region, a, b, X_AB);
      region.last_use = ++clock_;
      ++hits_;
      return &region;
    }
  }
  return nullptr;
}

PairCache::Region& PairCache::Make(const CollisionModel::Impl& a, const CollisionModel::Impl& b,
                                   double margin_m, const Isometry3d& X_AB) {
  const double skin_m = skin_m_ > 0 ? skin_m_ : SkinOf(a, b);
  const Isometry3d X_AB_built = BuildPose(regions_, a, b, margin_m, X_AB, skin_m);
  Region& region =
      *std::min_element(regions_.begin(), regions_.end(),
                        [](const Region& x, const Region& y) { return x.last_use < y.last_use; });
  region.a = a.id;
  region.b = b.id;
  region.version_a = a.geometry_version;
  region.version_b = b.geometry_version;
  region.margin_m = margin_m;
  region.skin_m = skin_m;
  region.X_AB = X_AB_built;
  region.streams = {};
  MoveOn(region, a, b, X_AB);
  region.candidates.clear();
  region.last_use = ++clock_;
  ++builds_;
  return region;
}

}  // namespace hs

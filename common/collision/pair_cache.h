#pragma once
// What a pair query learned near a pose, kept for the next queries of the
// same two objects (temporal coherence: at 1 kHz a tool moves a fraction of
// a millimetre between steps). A region holds, for a pose of B in A's frame
// and a skin s, every face pair that could meet within the margin while
// each object moves at most s from that pose relative to the other: the
// pairs whose boxes meet within margin + s and that neither face's plane
// keeps more than margin + s apart. A query inside a region tests those
// pairs alone, in the order the hierarchy traversal would reach them, and
// skips the traversal; a query outside every region builds one. Verlet
// lists, over face pairs instead of particles. Written here: FCL keeps
// nothing between queries (every collide starts at the hierarchies' roots),
// and no Debian library keeps such lists for a triangle-pair query.

#include <array>
#include <cstdint>
#include <vector>

#include "common/collision/collision_model.h"
#include "common/collision/triangle_sat.h"
#include "common/core/types.h"

namespace hs {

/// Kept by the caller for one pair of collision models between queries
/// (FindIntersectingTriangles' `cache`); a scene keeps one per tool and
/// object in contact. Answers are identical with or without it. One query
/// at a time.
class PairCache {
 public:
  /// Forgets every region, keeping their storage.
  void Clear();

  /// Forgets every region, and builds the next ones with a skin of
  /// `skin_m` metres (> 0) instead of kSkinRelative of the two models'
  /// radii: for a cache kept through one contact query alone, whose pair
  /// queries all lie within `skin_m` of its first (ComputeContact without
  /// a cache, when the depth along its direction is bounded that small).
  void Restart(double skin_m);

  /// kSkinRelative of the two models' radii, metres: the skin of a region
  /// unless Restart set one.
  static double DefaultSkin(const CollisionModel& a, const CollisionModel& b);

  /// Regions held, regions built since made, and queries answered from a
  /// region: for tests and benchmarks.
  int regions() const;
  int64_t builds() const { return builds_; }
  int64_t hits() const { return hits_; }

  // Internal to common/collision (triangle_pairs.cc).

  /// How far B has moved in A's frame along a run of queries, summed from
  /// each query to the next: B's turns in A's frame (RelativeTurn) and the
  /// larger of the shifts of the two models' centres (RelativeShift).
  /// Between two queries of the run, a point at distance r from its
  /// model's centre has moved at most the difference in shifted_m plus r
  /// times the difference in turned (each step's bound holds its motion,
  /// and a path is no shorter than its chord), and a direction fixed to B
  /// has turned by at most the difference in turned.
  struct Travel {
    double shifted_m = 0;
    double turned = 0;
  };

  /// A run of a region's queries, each near the last: the query at a
  /// contact's pose step after step, or the one at its depth. A contact
  /// whose depth lies within the skin has its two queries in one region,
  /// alternately; summed over one run, the jumps between the pose and the
  /// depth would spend every pair's gap twice a step.
  struct Stream {
    bool used = false;
    Isometry3d X_AB_last = Isometry3d::Identity();  // B's pose at its last query
    Travel travel;                                  // since its first query
  };
  static constexpr int kStreams = 2;

  /// A face pair of a region: A's face by its leaf position, B's by id,
  /// the edge cross that last separated them (PairHint::edge_pair), and
  /// until when they are known apart: while `stream`'s travel to the query
  /// (Region::to_query) has shifted_m + per_turn_m * turned under
  /// `apart_until`, metres, their boxes, planes or edge cross keep them
  /// beyond the margin. per_turn_m is how far the two faces move per
  /// radian of turn (their reach from their models' centres) plus the
  /// lever of that edge cross (PairHint).
  struct Candidate {
    int leaf_a;
    int face_b;
    int edge_pair = -1;
    int stream = 0;  // that last tested them
    double apart_until = -1;
    double per_turn_m = 0;
  };
  struct Region {
    uint64_t a = 0, b = 0;  // the models' ids; 0: free
    uint64_t version_a = 0, version_b = 0;
    double margin_m = 0;
    /// How far each object may move relative to the other, metres.
    double skin_m = 0;
    /// B's pose in A's frame that the region was built at: the query's
    /// that built it, or ahead of it along a steady motion (Make).
    Isometry3d X_AB = Isometry3d::Identity();
    /// Its queries, in runs: each joins the run whose last query lies
    /// nearest, or starts one while one is free. Unlike a bound from the
    /// region's pose, a run's travel lets a pair tested late in the region
    /// stay skipped as long as one tested early.
    std::array<Stream, kStreams> streams;
    /// The run of the current query, and each run's travel to it: its own
    /// for `stream`, through its last query for another (bounding the
    /// motion from any of its queries to this one).
    int stream = 0;
    std::array<Travel, kStreams> to_query;
    std::vector<Candidate> candidates;
    uint64_t last_use = 0;
  };

  /// The region of models `a` and `b` (at their current geometry) for
  /// `margin_m` that holds B's pose X_AB in A's frame, or null; a region
  /// found has moved on to X_AB (a run's travel counts the step there).
  Region* Find(const CollisionModel::Impl& a, const CollisionModel::Impl& b, double margin_m,
               const Isometry3d& X_AB);
  /// A region to build for a query at X_AB, its candidates empty: the
  /// least recently used one, its storage kept. Its skin and pose are set
  /// here: when the run of queries X_AB has just left moves on steadily,
  /// its pose is ahead of X_AB along that motion, so that the motion
  /// crosses the skin's whole width before it leaves (half the builds of a
  /// region at X_AB).
  Region& Make(const CollisionModel::Impl& a, const CollisionModel::Impl& b, double margin_m,
               const Isometry3d& X_AB);

  /// The skin of a region: this fraction of the sum of the two models'
  /// radii. Large enough that a hand-held tool stays inside a region for
  /// several steps, small enough that a region holds few pairs beside those
  /// that meet (contact_bench Coherent, docs/benchmarks.md).
  static constexpr double kSkinRelative = 8e-3;

  /// Rounding's share of a region's slack: relative to the size of the
  /// coordinates the pair tests see, far above the rounding of placing a
  /// face and of a plane distance.
  static constexpr double kRoundingRelative = 1e-9;

  /// Rounding's share for B at X_AB in A's frame, metres.
  static double Rounding(const CollisionModel::Impl& a, const CollisionModel::Impl& b,
                         const Isometry3d& X_AB);
  /// Whether a region at X_AB is worth building: its skin and rounding's
  /// share (its slack) below the two models' radii, so that it holds the
  /// pairs near the contact rather than nearly all (far from the origin,
  /// rounding's share grows with the coordinates).
  static bool Worthwhile(const CollisionModel::Impl& a, const CollisionModel::Impl& b,
                         const Isometry3d& X_AB);

 private:
  static constexpr int kRegions = 4;  // the contact's pose, its depth, spares
  std::array<Region, kRegions> regions_;
  double skin_m_ = 0;  // Restart's, or 0 for the default
  uint64_t clock_ = 0;
  int64_t builds_ = 0, hits_ = 0;
};

/// A bound on the angle (radians) through which B turns in A's frame
/// between poses X_AB_from and X_AB_to: |R u - u| <= it for every unit u.
double RelativeTurn(const Isometry3d& X_AB_from, const Isometry3d& X_AB_to);

/// The larger of the distances that A's centre moves in B's frame and B's
/// in A's frame between B's poses X_AB_from and X_AB_to in A's frame.
double RelativeShift(const CollisionModel::Impl& a, const CollisionModel::Impl& b,
                     const Isometry3d& X_AB_from, const Isometry3d& X_AB_to);

/// The most any point of A (in B's frame) or of B (in A's frame) moves
/// between B's poses X_AB_from and X_AB_to in A's frame, bounded through
/// each model's centre and radius. Metres.
double RelativeMotionBound(const CollisionModel::Impl& a, const CollisionModel::Impl& b,
                           const Isometry3d& X_AB_from, const Isometry3d& X_AB_to);

}  // namespace hs

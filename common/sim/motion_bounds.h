#pragma once
// Bounds on where an object goes during a step: its world box at a pose,
// the box swept between two poses, and how far any of its points travel.
// The scene uses them to pick candidate pairs and to split long steps into
// sub-steps (paper s.4, fig. 3 c).

#include "common/hds/haptic_object.h"

namespace hs {

/// `box` grown by `margin` (metres) on every side.
inline AlignedBox3d GrowBox(AlignedBox3d box, double margin) {
  box.min().array() -= margin;
  box.max().array() += margin;
  return box;
}

/// The world axis-aligned box around `object`'s own box posed at X_WO,
/// metres.
AlignedBox3d WorldBox(const HapticObject& object, const Isometry3d& X_WO);

/// How far any point of `object` moves from X_WO_from to X_WO_to along the
/// interpolation of InterpolatePose, at most, metres: the translation plus
/// the turned angle times the farthest box corner from the frame origin.
double Travel(const HapticObject& object, const Isometry3d& X_WO_from, const Isometry3d& X_WO_to);

/// A box holding `object` at every pose InterpolatePose gives between
/// X_WO_from and X_WO_to: the two end boxes' hull, grown by twice the
/// turning part of Travel. World frame, metres.
AlignedBox3d SweptBox(const HapticObject& object, const Isometry3d& X_WO_from,
                      const Isometry3d& X_WO_to);

/// The pose a fraction `s` in [0, 1] of the way: translation linear,
/// rotation by spherical interpolation (shortest way).
Isometry3d InterpolatePose(const Isometry3d& X_from, const Isometry3d& X_to, double s);

/// The fewest sub-steps that keep each one's travel strictly under
/// `max_travel_m` (paper s.4: under the smallest box edge), capped at
/// `max_substeps`: 1 + floor(travel / max_travel).
int SubstepCount(double travel_m, double max_travel_m, int max_substeps);

}  // namespace hs

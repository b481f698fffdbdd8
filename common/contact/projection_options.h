#pragma once
// Internal to common/contact: the one reading of the paper's method that is
// left open, as an option, so that tests can show why the default is what it
// is. Production code calls ReconstructByProjection(context) (paper_method.h).

#include "common/contact/contact_context.h"
#include "common/contact/contact_set.h"

namespace hs {

/// When a vertex counts as penetrating in one projection plane.
enum class PenetrationTest {
  /// The paper's own criterion (s.4: "If d_ij >= 0, the corresponding vertex
  /// V_m[i] penetrates the fixed polyhedron"): the line through the vertex
  /// along the projected direction crosses a candidate edge behind it.
  /// Equivalently: the vertex lies in the projection of a paired triangle of
  /// the other object swept along the direction of motion. The default.
  kBackwardCrossing,
  /// The plain reading of "the vertex penetrates": it lies inside the
  /// projection of a paired triangle of the other object. It misses every
  /// face seen edge-on, so a vertex pressed into a face along the face's
  /// normal is never found (paper_method_test shows it on fig. 8 (a)).
  kInsideTriangle,
};

/// Options of ReconstructByProjection; the defaults are the production ones.
struct ProjectionOptions {
  PenetrationTest penetration = PenetrationTest::kBackwardCrossing;
  /// Skip the crossings that cannot come within the tolerance of the
  /// deepest (a speed-up with the same answer; tests compare it with false,
  /// which computes every crossing).
  bool skip_shallow_crossings = true;
  /// Run every plane in full. Otherwise a plane that cannot change the
  /// answer stops early, and ContactSetF::plane_depths_m holds for it a
  /// lower bound of its depth (a speed-up with the same answer).
  bool exact_plane_depths = false;
};

/// ReconstructByProjection (paper_method.h) with explicit options; the result
/// is in F's frame.
ContactSetF ReconstructByProjection(const ContactContext& context,
                                    const ProjectionOptions& options);

}  // namespace hs

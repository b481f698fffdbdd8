#pragma once
// SweptPlaneBounds (triangle_sat.h) of many face pairs, several at a time
// in the lanes of the machine's widest vectors (Google Highway, the target
// chosen when the program runs, so that the binaries run on any x86-64):
// bit for bit the scalar bounds, pair by pair.

#include <span>

#include "common/collision/triangle_sat.h"

namespace hs {

/// out[i] = SweptPlaneBounds(a[i], b[i], direction, margin, within) for
/// each i, the triangles read through their corners (so that gathering a
/// query's few hundred pairs copies no triangle); `a` and `out` hold
/// b.size() entries.
void SweptPlaneBoundsBatch(std::span<const TriangleCorners> a, std::span<const TriangleCorners> b,
                           const Vector3d& direction, double margin, Interval within,
                           std::span<SweptIntervals> out);

}  // namespace hs

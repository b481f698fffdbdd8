#pragma once
// Finding vertices that share a position, within a tolerance. Used to report
// duplicate vertices (mesh_report.h) and to weld them on import (model/).

#include <span>
#include <vector>

#include "common/core/types.h"

namespace hs {

/// For each vertex, the smallest id of a vertex within `tolerance` (metres,
/// Euclidean) of it, following chains: result[v] == v for the vertices that
/// are kept, result[v] < v for those that duplicate an earlier one.
/// tolerance == 0 finds exact duplicates. Positions must be finite.
std::vector<VertexId> FindWeldTargets(std::span<const Vector3d> positions, double tolerance);

}  // namespace hs

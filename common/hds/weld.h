#pragma once
// Finding vertices that share a position, within a tolerance. Used to report
// duplicate vertices (mesh_report.h) and to weld them on import (model/).

#include <span>
#include <vector>

#include "common/core/types.h"

namespace hs {

/// For each vertex in id order: itself when no earlier kept vertex lies
/// within `tolerance` (metres, Euclidean), else the smallest such kept
/// vertex. result[v] == v marks the kept vertices.
/// tolerance == 0 finds exact duplicates. Positions must be finite.
std::vector<VertexId> FindWeldTargets(std::span<const Vector3d> positions, double tolerance);

}  // namespace hs

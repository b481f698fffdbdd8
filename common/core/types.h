#pragma once
// Vocabulary shared by every layer: Eigen aliases and feature ids.
// Units across the project are SI: metres, seconds, kilograms, newtons. A model
// file's own unit is converted to metres at import (ImportOptions::unit_scale in
// common/model/import.h).

#include <Eigen/Geometry>
#include <algorithm>
#include <cstdint>

namespace hs {

using Vector3d = Eigen::Vector3d;
using Matrix3d = Eigen::Matrix3d;
using Isometry3d = Eigen::Isometry3d;
using AlignedBox3d = Eigen::AlignedBox3d;

/// Index of a vertex in one object's HDS (0-based, dense).
using VertexId = int32_t;
/// Index of an undirected edge in one object's HDS (0-based, dense).
using EdgeId = int32_t;
/// Index of a triangular face ("element plate") in one object's HDS.
using FaceId = int32_t;
/// Index into one object's material table.
using MaterialId = int32_t;
/// Index of the polygon of the source file a face was triangulated from;
/// kNoPolygon when the face did not come from a file.
using PolygonId = int32_t;
inline constexpr PolygonId kNoPolygon = -1;

}  // namespace hs

#pragma once
// The polygons of a model file as a reader hands them to cleaning: what the
// file says, in file units, before triangulation, scaling, welding and
// dropping. Internal to common/model.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "common/core/types.h"

namespace hs {

/// Polygons of one model file, all meshes merged, with materials and the id
/// of the file polygon each comes from.
struct RawMesh {
  /// Vertex positions in the file's unit, the file's node transforms applied.
  std::vector<Vector3d> positions;
  /// Polygon p has the vertex indices corners[offsets[p] .. offsets[p + 1]),
  /// at least 3, counter-clockwise seen from outside for closed meshes.
  std::vector<int32_t> corners;
  std::vector<int32_t> offsets = {0};
  /// Per polygon: index into material_names.
  std::vector<int32_t> polygon_materials;
  /// Per polygon: id of the file polygon it comes from. A reader that
  /// triangulates by itself (Coin) gives every triangle of one file polygon
  /// the same id, so several entries may share an id.
  std::vector<PolygonId> polygon_ids;
  /// Names of the file's materials; "" stands for "the file names none" and
  /// gets the name of ImportOptions::default_material.
  std::vector<std::string> material_names;

  int num_polygons() const { return static_cast<int>(polygon_ids.size()); }

  /// Vertex indices of polygon `p`.
  std::span<const int32_t> polygon(int p) const {
    return std::span<const int32_t>(corners.data() + offsets[p], offsets[p + 1] - offsets[p]);
  }

  /// Appends a polygon over `vertices` (indices into positions).
  void AddPolygon(std::span<const int32_t> vertices, int32_t material, PolygonId id) {
    corners.insert(corners.end(), vertices.begin(), vertices.end());
    offsets.push_back(static_cast<int32_t>(corners.size()));
    polygon_materials.push_back(material);
    polygon_ids.push_back(id);
  }
};

}  // namespace hs

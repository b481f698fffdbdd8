#pragma once
// Test helper for the readers' tests: the model files of tests/data, and
// what a RawMesh of closed models must satisfy, computed from its polygons
// alone (their oracle).

#include <fstream>
#include <sstream>
#include <string>

#include "common/model/raw_mesh.h"
#include "tests/common/test_data_dir.h"

namespace hs::testing_raw_mesh {

/// The bytes of tests/data/`name`.
inline std::string DataBytes(const std::string& name) {
  std::ifstream in(TestDataPath(name), std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

/// The volume the polygons enclose (divergence theorem over fans of each
/// polygon): positive when they turn counter-clockwise seen from outside.
inline double SignedVolume(const RawMesh& mesh) {
  double six_volume = 0;
  for (int p = 0; p < mesh.num_polygons(); ++p) {
    const auto corners = mesh.polygon(p);
    for (size_t i = 1; i + 1 < corners.size(); ++i) {
      six_volume += mesh.positions[corners[0]].dot(
          mesh.positions[corners[i]].cross(mesh.positions[corners[i + 1]]));
    }
  }
  return six_volume / 6;
}

/// The box of the corners the polygons use.
inline AlignedBox3d UsedBox(const RawMesh& mesh) {
  AlignedBox3d box;
  for (const int32_t corner : mesh.corners) box.extend(mesh.positions[corner]);
  return box;
}

/// Polygon p's outward side of an axis-aligned box as "-x", "+y", ...
inline std::string Side(const RawMesh& mesh, int p) {
  const auto corners = mesh.polygon(p);
  Vector3d n = Vector3d::Zero();
  for (size_t i = 0; i < corners.size(); ++i) {
    n += mesh.positions[corners[i]].cross(mesh.positions[corners[(i + 1) % corners.size()]]);
  }
  int axis;
  n.cwiseAbs().maxCoeff(&axis);
  return std::string(n[axis] > 0 ? "+" : "-") + "xyz"[axis];
}

/// The name of polygon p's material.
inline const std::string& MaterialName(const RawMesh& mesh, int p) {
  return mesh.material_names[mesh.polygon_materials[p]];
}

}  // namespace hs::testing_raw_mesh

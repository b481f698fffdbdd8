#pragma once
// What is wrong or notable about a mesh: the validation report of the HDS.

#include <vector>

#include "common/hds/haptic_object.h"

namespace hs {

struct MeshReport {
  /// Faces whose area is zero up to rounding: twice the area is at most
  /// 1e-12 times the square of the face's longest edge.
  std::vector<FaceId> degenerate_faces;
  /// Vertices within the tolerance of an earlier vertex.
  int duplicate_vertices = 0;
  /// Vertices that no face uses.
  int unreferenced_vertices = 0;
  /// Edges with exactly one adjacent face.
  int boundary_edges = 0;
  /// Edges with three or more adjacent faces.
  int non_manifold_edges = 0;
  /// Every edge has exactly two faces: the mesh bounds a volume.
  bool closed = false;
  /// Every two-face edge is walked in opposite directions by its two faces.
  bool consistently_oriented = false;
  /// V - E + F over the vertices that faces use (2 per sphere-like closed
  /// component, 0 per torus).
  int euler_characteristic = 0;
  /// Groups of faces connected through shared edges.
  int connected_components = 0;
};

/// Inspects `object`. `relative_tolerance` times the bounding-box diagonal is
/// the distance under which two vertices count as duplicates.
MeshReport InspectMesh(const HapticObject& object, double relative_tolerance = 1e-9);

}  // namespace hs

#include "common/hds/mesh_report.h"

#include <numeric>

#include "common/hds/triangle.h"
#include "common/hds/weld.h"

namespace hs {
namespace {

// +1 when `face` walks edge (a, b) from a to b, -1 when from b to a.
int Direction(const Face& face, VertexId a, VertexId b) {
  for (int i = 0; i < 3; ++i) {
    if (face.vertices[i] == a && face.vertices[(i + 1) % 3] == b) return 1;
  }
  return -1;
}

int CountComponents(const HapticObject& object) {
  std::vector<FaceId> parent(object.num_faces());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](FaceId f) {
    while (parent[f] != f) f = parent[f] = parent[parent[f]];
    return f;
  };
  for (EdgeId e = 0; e < object.num_edges(); ++e) {
    auto faces = object.EdgeFaces(e);
    for (size_t i = 1; i < faces.size(); ++i) parent[find(faces[i])] = find(faces[0]);
  }
  int roots = 0;
  for (FaceId f = 0; f < object.num_faces(); ++f) roots += find(f) == f;
  return roots;
}

}  // namespace

MeshReport InspectMesh(const HapticObject& object, double relative_tolerance) {
  MeshReport report;
  for (FaceId f = 0; f < object.num_faces(); ++f) {
    const auto& v = object.face(f).vertices;
    if (IsDegenerateTriangle(object.position(v[0]), object.position(v[1]), object.position(v[2])))
      report.degenerate_faces.push_back(f);
  }
  const double tolerance = relative_tolerance * object.bounding_box().diagonal().norm();
  const std::vector<VertexId> targets = FindWeldTargets(object.positions(), tolerance);
  int used_vertices = 0;
  for (VertexId v = 0; v < object.num_vertices(); ++v) {
    report.duplicate_vertices += targets[v] != v;
    if (object.VertexFaces(v).empty()) {
      ++report.unreferenced_vertices;
    } else {
      ++used_vertices;
    }
  }
  report.consistently_oriented = true;
  for (EdgeId e = 0; e < object.num_edges(); ++e) {
    auto faces = object.EdgeFaces(e);
    if (faces.size() == 1) ++report.boundary_edges;
    if (faces.size() > 2) ++report.non_manifold_edges;
    if (faces.size() == 2) {
      const auto [a, b] = object.edge(e).vertices;
      if (Direction(object.face(faces[0]), a, b) == Direction(object.face(faces[1]), a, b)) {
        report.consistently_oriented = false;
      }
    }
  }
  report.closed = report.boundary_edges == 0 && report.non_manifold_edges == 0;
  report.euler_characteristic = used_vertices - object.num_edges() + object.num_faces();
  report.connected_components = CountComponents(object);
  return report;
}

}  // namespace hs

#include "common/contact/side_contact.h"

#include <algorithm>

namespace hs {
namespace {

template <typename T>
void SortUnique(std::vector<T>& v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

}  // namespace

SideContact AggregateSide(const HapticObject& object, std::span<const VertexId> vertices,
                          std::span<const EdgeId> touched_edges,
                          std::span<const FaceId> touched_faces) {
  SideContact side;
  side.vertices.assign(vertices.begin(), vertices.end());
  SortUnique(side.vertices);
  side.edges.assign(touched_edges.begin(), touched_edges.end());
  side.faces.assign(touched_faces.begin(), touched_faces.end());
  auto is_contact = [&](VertexId v) {
    return std::binary_search(side.vertices.begin(), side.vertices.end(), v);
  };
  for (VertexId v : side.vertices) {
    for (EdgeId e : object.VertexEdges(v)) {
      const Edge& edge = object.edge(e);
      if (is_contact(edge.vertices[0]) && is_contact(edge.vertices[1])) side.edges.push_back(e);
    }
    for (FaceId f : object.VertexFaces(v)) {
      const auto& c = object.face(f).vertices;
      if (is_contact(c[0]) && is_contact(c[1]) && is_contact(c[2])) side.faces.push_back(f);
    }
  }
  SortUnique(side.edges);
  SortUnique(side.faces);
  side.kind = !side.faces.empty()      ? FeatureKind::kFace
              : !side.edges.empty()    ? FeatureKind::kEdge
              : !side.vertices.empty() ? FeatureKind::kVertex
                                       : FeatureKind::kNone;
  return side;
}

}  // namespace hs

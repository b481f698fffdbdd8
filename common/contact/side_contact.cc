#include "common/contact/side_contact.h"

#include <algorithm>
#include <cstdint>
#include <vector>

#include "common/core/scratch.h"

namespace hs {
namespace {

// AggregateSide's marks, kept from call to call.
struct ContactMarks {
  std::vector<uint8_t> is_contact;
};

template <typename T>
void SortUnique(std::vector<T>& v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

}  // namespace

void AggregateSide(const HapticObject& object, std::span<const VertexId> vertices,
                   std::span<const EdgeId> touched_edges, std::span<const FaceId> touched_faces,
                   SideContact& side) {
  side.vertices.assign(vertices.begin(), vertices.end());
  SortUnique(side.vertices);
  side.edges.assign(touched_edges.begin(), touched_edges.end());
  side.faces.assign(touched_faces.begin(), touched_faces.end());
  // One mark per vertex of the object, set for the contact vertices and
  // cleared on the way out: a lookup per neighbour, whatever their number.
  std::vector<uint8_t>& is_contact = Scratch<ContactMarks>().is_contact;
  if (is_contact.size() < static_cast<size_t>(object.num_vertices())) {
    is_contact.resize(object.num_vertices(), 0);
  }
  // Each edge and face is taken from its lowest contact vertex only: the
  // sorts below then see each once, besides the touched ones.
  for (VertexId v : side.vertices) is_contact[v] = 1;
  for (VertexId v : side.vertices) {
    for (EdgeId e : object.VertexEdges(v)) {
      const auto& ends = object.edge(e).vertices;
      const VertexId other = ends[0] == v ? ends[1] : ends[0];
      if (other > v && is_contact[other]) side.edges.push_back(e);
    }
    for (FaceId f : object.VertexFaces(v)) {
      const auto& c = object.face(f).vertices;
      if (std::min({c[0], c[1], c[2]}) == v && is_contact[c[0]] && is_contact[c[1]] &&
          is_contact[c[2]]) {
        side.faces.push_back(f);
      }
    }
  }
  for (VertexId v : side.vertices) is_contact[v] = 0;
  SortUnique(side.edges);
  SortUnique(side.faces);
  side.kind = !side.faces.empty()      ? FeatureKind::kFace
              : !side.edges.empty()    ? FeatureKind::kEdge
              : !side.vertices.empty() ? FeatureKind::kVertex
                                       : FeatureKind::kNone;
}

}  // namespace hs

#pragma once
// The Haptic Data Structure (paper s.2, fig. 2) for one rigid object:
// object -> faces ("element plates", each with a material and the polygon of
// the source file it came from) -> unique edges (with their adjacent faces)
// -> vertices (with their adjacent faces and edges).
//
// Topology is fixed at creation; geometry (vertex positions) and face
// materials may change afterwards. Every geometry change bumps
// geometry_version() and stamps the moved vertices, so the collision layer
// can ask what moved since the version it last saw.
//
// Coordinates are in the object's own frame O, in metres.

#include <array>
#include <span>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "common/core/types.h"
#include "common/hds/material.h"

namespace hs {

/// One triangle as given to HapticObject::Create.
struct FaceInput {
  /// Vertex ids, counter-clockwise seen from outside for closed meshes.
  std::array<VertexId, 3> vertices{};
  /// Index into MeshInput::materials.
  MaterialId material = 0;
  /// Polygon of the source file this triangle was cut from; kNoPolygon if none.
  PolygonId source_polygon = kNoPolygon;
};

/// Everything needed to build one HapticObject.
struct MeshInput {
  /// Vertex positions p_OV in the object frame, metres.
  std::vector<Vector3d> positions;
  std::vector<FaceInput> faces;
  /// At least one material when there are faces.
  std::vector<Material> materials;
};

/// A triangular face of the HDS.
struct Face {
  std::array<VertexId, 3> vertices{};
  /// edges[i] joins vertices[i] and vertices[(i + 1) % 3].
  std::array<EdgeId, 3> edges{};
  MaterialId material = 0;
  PolygonId source_polygon = kNoPolygon;
};

/// An undirected edge; vertices[0] < vertices[1].
struct Edge {
  std::array<VertexId, 2> vertices{};
};

class HapticObject {
 public:
  /// Builds the HDS from `input`. INVALID_ARGUMENT when a coordinate is not
  /// finite, a vertex or material index is out of range, a face repeats a
  /// vertex, there are no faces, or a material is invalid. Degenerate
  /// (zero-area) faces, duplicate vertices and open or non-manifold edges are
  /// accepted; InspectMesh() reports them.
  static absl::StatusOr<HapticObject> Create(std::string name, MeshInput input);

  const std::string& name() const { return name_; }
  int num_vertices() const { return static_cast<int>(positions_.size()); }
  int num_edges() const { return static_cast<int>(edges_.size()); }
  int num_faces() const { return static_cast<int>(faces_.size()); }

  /// Vertex positions p_OV, object frame, metres.
  std::span<const Vector3d> positions() const { return positions_; }
  const Vector3d& position(VertexId v) const { return positions_[v]; }
  std::span<const Face> faces() const { return faces_; }
  const Face& face(FaceId f) const { return faces_[f]; }
  std::span<const Edge> edges() const { return edges_; }
  const Edge& edge(EdgeId e) const { return edges_[e]; }
  std::span<const Material> materials() const { return materials_; }
  const Material& face_material(FaceId f) const { return materials_[faces_[f].material]; }

  /// Faces that contain edge `e` (1 on an open boundary, 2 on a manifold
  /// interior edge, more on a non-manifold edge).
  std::span<const FaceId> EdgeFaces(EdgeId e) const;
  /// Faces that contain vertex `v`.
  std::span<const FaceId> VertexFaces(VertexId v) const;
  /// Edges that end at vertex `v`.
  std::span<const EdgeId> VertexEdges(VertexId v) const;
  /// The edge joining `a` and `b`, or -1 when they are not joined.
  EdgeId FindEdge(VertexId a, VertexId b) const;

  /// Axis-aligned bounding box in the object frame, metres.
  const AlignedBox3d& bounding_box() const { return bounding_box_; }
  /// Length of the shortest side of bounding_box(), metres. The paper keeps a
  /// step shorter than this so that no object passes through another.
  double smallest_box_edge() const;

  /// Starts at 1; +1 for every successful geometry modification.
  uint64_t geometry_version() const { return geometry_version_; }
  /// Starts at 1; +1 for every successful material change.
  uint64_t material_version() const { return material_version_; }
  /// The vertices moved after geometry version `since`, in id order.
  std::vector<VertexId> VerticesChangedSince(uint64_t since) const;
  /// The faces with a vertex moved after geometry version `since`, in id order.
  std::vector<FaceId> FacesChangedSince(uint64_t since) const;

  /// Moves vertices `ids[i]` to `positions[i]` (object frame, metres).
  /// All or nothing: INVALID_ARGUMENT and no change when the spans differ in
  /// length, an id is out of range, or a position is not finite.
  absl::Status MoveVertices(std::span<const VertexId> ids, std::span<const Vector3d> positions);
  /// Gives face `f` material `m`. INVALID_ARGUMENT and no change when either
  /// id is out of range.
  absl::Status SetFaceMaterial(FaceId f, MaterialId m);
  /// Replaces the parameters of material `m`. INVALID_ARGUMENT and no change
  /// when `m` is out of range or `material` is invalid.
  absl::Status SetMaterial(MaterialId m, Material material);

 private:
  HapticObject() = default;
  void BuildAdjacency();
  void UpdateBoundingBox();

  std::string name_;
  std::vector<Vector3d> positions_;
  std::vector<Face> faces_;
  std::vector<Edge> edges_;
  std::vector<Material> materials_;
  // Compressed rows: the neighbours of item i are
  // ids[offsets[i] .. offsets[i + 1]).
  std::vector<int32_t> edge_face_offsets_, edge_face_ids_;
  std::vector<int32_t> vertex_face_offsets_, vertex_face_ids_;
  std::vector<int32_t> vertex_edge_offsets_, vertex_edge_ids_;
  AlignedBox3d bounding_box_;
  uint64_t geometry_version_ = 1;
  uint64_t material_version_ = 1;
  // Geometry version at which each vertex last moved (1 = never moved).
  std::vector<uint64_t> vertex_versions_;
};

}  // namespace hs

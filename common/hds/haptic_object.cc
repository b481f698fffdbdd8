#include "common/hds/haptic_object.h"

#include <algorithm>
#include <unordered_map>
#include <utility>

#include "absl/strings/str_cat.h"
#include "common/core/status_macros.h"

namespace hs {
namespace {

// Compressed rows of `num_rows` lists from (row, value) pairs, values kept in
// the order they were given.
void BuildRows(int num_rows, const std::vector<std::pair<int32_t, int32_t>>& pairs,
               std::vector<int32_t>& offsets, std::vector<int32_t>& ids) {
  offsets.assign(num_rows + 1, 0);
  for (const auto& [row, value] : pairs) ++offsets[row + 1];
  for (int i = 0; i < num_rows; ++i) offsets[i + 1] += offsets[i];
  ids.assign(pairs.size(), 0);
  std::vector<int32_t> cursor(offsets.begin(), offsets.end() - 1);
  for (const auto& [row, value] : pairs) ids[cursor[row]++] = value;
}

std::span<const int32_t> Row(const std::vector<int32_t>& offsets, const std::vector<int32_t>& ids,
                             int32_t i) {
  return std::span<const int32_t>(ids.data() + offsets[i], offsets[i + 1] - offsets[i]);
}

absl::Status ValidateInput(const MeshInput& input) {
  if (input.faces.empty()) return absl::InvalidArgumentError("mesh has no faces");
  if (input.materials.empty()) return absl::InvalidArgumentError("mesh has no material");
  for (size_t i = 0; i < input.materials.size(); ++i) {
    HS_RETURN_IF_ERROR(ValidateMaterial(input.materials[i]));
  }
  for (size_t i = 0; i < input.positions.size(); ++i) {
    if (!input.positions[i].allFinite()) {
      return absl::InvalidArgumentError(absl::StrCat("vertex ", i, " has a non-finite coordinate"));
    }
  }
  const auto num_vertices = static_cast<int64_t>(input.positions.size());
  const auto num_materials = static_cast<int64_t>(input.materials.size());
  for (size_t f = 0; f < input.faces.size(); ++f) {
    const FaceInput& face = input.faces[f];
    for (VertexId v : face.vertices) {
      if (v < 0 || v >= num_vertices) {
        return absl::InvalidArgumentError(
            absl::StrCat("face ", f, " names vertex ", v, " but there are ", num_vertices));
      }
    }
    const auto& v = face.vertices;
    if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2]) {
      return absl::InvalidArgumentError(absl::StrCat("face ", f, " repeats a vertex"));
    }
    if (face.material < 0 || face.material >= num_materials) {
      return absl::InvalidArgumentError(absl::StrCat("face ", f, " names material ", face.material,
                                                     " but there are ", num_materials));
    }
  }
  return absl::OkStatus();
}

}  // namespace

absl::StatusOr<HapticObject> HapticObject::Create(std::string name, MeshInput input) {
  HS_RETURN_IF_ERROR(ValidateInput(input));
  HapticObject object;
  object.name_ = std::move(name);
  object.positions_ = std::move(input.positions);
  object.materials_ = std::move(input.materials);
  object.faces_.reserve(input.faces.size());
  for (const FaceInput& in : input.faces) {
    object.faces_.push_back(Face{in.vertices, {}, in.material, in.source_polygon});
  }
  object.vertex_versions_.assign(object.positions_.size(), 1);
  object.BuildAdjacency();
  object.UpdateBoundingBox();
  return object;
}

void HapticObject::BuildAdjacency() {
  const int num_v = num_vertices();
  std::unordered_map<uint64_t, EdgeId> edge_of_pair;
  edge_of_pair.reserve(faces_.size() * 2);
  std::vector<std::pair<int32_t, int32_t>> edge_face, vertex_face, vertex_edge;
  edge_face.reserve(faces_.size() * 3);
  vertex_face.reserve(faces_.size() * 3);
  for (FaceId f = 0; f < num_faces(); ++f) {
    Face& face = faces_[f];
    for (int i = 0; i < 3; ++i) {
      VertexId a = face.vertices[i], b = face.vertices[(i + 1) % 3];
      if (a > b) std::swap(a, b);
      const uint64_t key = (static_cast<uint64_t>(a) << 32) | static_cast<uint32_t>(b);
      auto [it, inserted] = edge_of_pair.try_emplace(key, num_edges());
      if (inserted) {
        edges_.push_back(Edge{{a, b}});
        vertex_edge.emplace_back(a, it->second);
        vertex_edge.emplace_back(b, it->second);
      }
      face.edges[i] = it->second;
      edge_face.emplace_back(it->second, f);
      vertex_face.emplace_back(face.vertices[i], f);
    }
  }
  BuildRows(num_edges(), edge_face, edge_face_offsets_, edge_face_ids_);
  BuildRows(num_v, vertex_face, vertex_face_offsets_, vertex_face_ids_);
  BuildRows(num_v, vertex_edge, vertex_edge_offsets_, vertex_edge_ids_);
}

void HapticObject::UpdateBoundingBox() {
  bounding_box_.setEmpty();
  for (const Face& face : faces_) {
    for (VertexId v : face.vertices) bounding_box_.extend(positions_[v]);
  }
}

std::span<const FaceId> HapticObject::EdgeFaces(EdgeId e) const {
  return Row(edge_face_offsets_, edge_face_ids_, e);
}

std::span<const FaceId> HapticObject::VertexFaces(VertexId v) const {
  return Row(vertex_face_offsets_, vertex_face_ids_, v);
}

std::span<const EdgeId> HapticObject::VertexEdges(VertexId v) const {
  return Row(vertex_edge_offsets_, vertex_edge_ids_, v);
}

EdgeId HapticObject::FindEdge(VertexId a, VertexId b) const {
  if (a < 0 || a >= num_vertices()) return -1;
  for (EdgeId e : VertexEdges(a)) {
    const Edge& edge = edges_[e];
    if (edge.vertices[0] == b || edge.vertices[1] == b) return e;
  }
  return -1;
}

double HapticObject::smallest_box_edge() const { return bounding_box_.sizes().minCoeff(); }

std::vector<VertexId> HapticObject::VerticesChangedSince(uint64_t since) const {
  std::vector<VertexId> changed;
  for (VertexId v = 0; v < num_vertices(); ++v) {
    if (vertex_versions_[v] > since) changed.push_back(v);
  }
  return changed;
}

std::vector<FaceId> HapticObject::FacesChangedSince(uint64_t since) const {
  std::vector<FaceId> changed;
  for (FaceId f = 0; f < num_faces(); ++f) {
    const auto& v = faces_[f].vertices;
    if (std::max({vertex_versions_[v[0]], vertex_versions_[v[1]], vertex_versions_[v[2]]}) >
        since) {
      changed.push_back(f);
    }
  }
  return changed;
}

absl::Status HapticObject::MoveVertices(std::span<const VertexId> ids,
                                        std::span<const Vector3d> positions) {
  if (ids.size() != positions.size()) {
    return absl::InvalidArgumentError(
        absl::StrCat("MoveVertices: ", ids.size(), " ids but ", positions.size(), " positions"));
  }
  for (size_t i = 0; i < ids.size(); ++i) {
    if (ids[i] < 0 || ids[i] >= num_vertices()) {
      return absl::InvalidArgumentError(
          absl::StrCat("MoveVertices: vertex ", ids[i], " out of range [0, ", num_vertices(), ")"));
    }
    if (!positions[i].allFinite()) {
      return absl::InvalidArgumentError(
          absl::StrCat("MoveVertices: position for vertex ", ids[i], " is not finite"));
    }
  }
  if (ids.empty()) return absl::OkStatus();
  ++geometry_version_;
  for (size_t i = 0; i < ids.size(); ++i) {
    positions_[ids[i]] = positions[i];
    vertex_versions_[ids[i]] = geometry_version_;
  }
  UpdateBoundingBox();
  return absl::OkStatus();
}

absl::Status HapticObject::SetFaceMaterial(FaceId f, MaterialId m) {
  if (f < 0 || f >= num_faces()) {
    return absl::InvalidArgumentError(absl::StrCat("face ", f, " out of range"));
  }
  if (m < 0 || m >= static_cast<int>(materials_.size())) {
    return absl::InvalidArgumentError(absl::StrCat("material ", m, " out of range"));
  }
  faces_[f].material = m;
  ++material_version_;
  return absl::OkStatus();
}

absl::Status HapticObject::SetMaterial(MaterialId m, Material material) {
  if (m < 0 || m >= static_cast<int>(materials_.size())) {
    return absl::InvalidArgumentError(absl::StrCat("material ", m, " out of range"));
  }
  HS_RETURN_IF_ERROR(ValidateMaterial(material));
  materials_[m] = std::move(material);
  ++material_version_;
  return absl::OkStatus();
}

}  // namespace hs

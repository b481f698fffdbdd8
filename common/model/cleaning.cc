#include "common/model/cleaning.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <unordered_map>
#include <vector>

#include "absl/container/flat_hash_set.h"
#include "absl/strings/str_cat.h"
#include "common/hds/triangle.h"
#include "common/hds/weld.h"

namespace hs {

absl::Status ValidateImportOptions(const ImportOptions& options) {
  if (!(std::isfinite(options.unit_scale) && options.unit_scale > 0)) {
    return absl::InvalidArgumentError(
        absl::StrCat("unit_scale = ", options.unit_scale, " must be finite and > 0"));
  }
  if (!(std::isfinite(options.weld_relative_tolerance) && options.weld_relative_tolerance >= 0)) {
    return absl::InvalidArgumentError(absl::StrCat(
        "weld_relative_tolerance = ", options.weld_relative_tolerance, " must be finite and >= 0"));
  }
  if (absl::Status status = ValidateMaterial(options.default_material); !status.ok()) {
    return absl::InvalidArgumentError(absl::StrCat("default_material: ", status.message()));
  }
  return absl::OkStatus();
}

absl::Status ValidateRawMesh(const RawMesh& mesh) {
  constexpr size_t kMaxIndex = std::numeric_limits<int32_t>::max();
  if (mesh.positions.size() > kMaxIndex || mesh.corners.size() > kMaxIndex) {
    return absl::InvalidArgumentError("more than 2^31 - 1 vertices or polygon corners");
  }
  const size_t num_polygons = mesh.polygon_ids.size();
  if (mesh.offsets.size() != num_polygons + 1 || mesh.polygon_materials.size() != num_polygons ||
      mesh.offsets.front() != 0 ||
      static_cast<size_t>(mesh.offsets.back()) != mesh.corners.size()) {
    return absl::InvalidArgumentError("inconsistent polygon arrays");
  }
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    if (!mesh.positions[v].allFinite()) {
      const Vector3d& p = mesh.positions[v];
      return absl::InvalidArgumentError(absl::StrCat("vertex ", v, " has a non-finite coordinate (",
                                                     p.x(), ", ", p.y(), ", ", p.z(), ")"));
    }
  }
  const auto num_vertices = static_cast<int64_t>(mesh.positions.size());
  const auto num_materials = static_cast<int64_t>(mesh.material_names.size());
  for (size_t p = 0; p < num_polygons; ++p) {
    if (mesh.offsets[p + 1] - mesh.offsets[p] < 3) {
      return absl::InvalidArgumentError(absl::StrCat("polygon ", p, " has fewer than 3 corners"));
    }
    for (int32_t v : mesh.polygon(static_cast<int>(p))) {
      if (v < 0 || v >= num_vertices) {
        return absl::InvalidArgumentError(
            absl::StrCat("polygon ", p, " names vertex ", v, " but there are ", num_vertices));
      }
    }
    const int32_t m = mesh.polygon_materials[p];
    if (m < 0 || m >= num_materials) {
      return absl::InvalidArgumentError(
          absl::StrCat("polygon ", p, " names material ", m, " but there are ", num_materials));
    }
  }
  return absl::OkStatus();
}

absl::StatusOr<CleanedMesh> CleanMesh(const RawMesh& raw, std::span<const FaceInput> triangles,
                                      const ImportOptions& options) {
  CleanedMesh out;
  CleaningReport& report = out.report;
  const int num_vertices = static_cast<int>(raw.positions.size());
  report.input_vertices = num_vertices;
  {
    std::vector<PolygonId> ids = raw.polygon_ids;
    std::sort(ids.begin(), ids.end());
    report.input_polygons = static_cast<int>(std::unique(ids.begin(), ids.end()) - ids.begin());
  }
  report.input_triangles = static_cast<int>(triangles.size());
  if (triangles.empty()) return absl::InvalidArgumentError("no triangles");

  // 1. File unit -> metres.
  std::vector<Vector3d> positions(raw.positions.size());
  for (int v = 0; v < num_vertices; ++v) {
    positions[v] = raw.positions[v] * options.unit_scale;
    if (!positions[v].allFinite()) {
      return absl::InvalidArgumentError(
          absl::StrCat("vertex ", v, " overflows at unit_scale ", options.unit_scale));
    }
  }

  // 2. Weld, with the tolerance taken relative to the part of the model that
  // can be touched: a stray unused vertex must not widen it.
  AlignedBox3d box;
  for (const FaceInput& t : triangles) {
    for (VertexId v : t.vertices) box.extend(positions[v]);
  }
  const double diagonal = box.diagonal().norm();
  const double tolerance =
      std::isfinite(diagonal) ? options.weld_relative_tolerance * diagonal : 0.0;
  const std::vector<VertexId> target = FindWeldTargets(positions, tolerance);
  for (VertexId v = 0; v < num_vertices; ++v) report.welded_vertices += target[v] != v;

  // 3. Drop degenerate, then duplicate triangles.
  std::vector<FaceInput> kept;
  kept.reserve(triangles.size());
  absl::flat_hash_set<std::array<VertexId, 3>> seen;
  seen.reserve(triangles.size());
  for (const FaceInput& t : triangles) {
    FaceInput face = t;
    for (VertexId& v : face.vertices) v = target[v];
    const auto& [a, b, c] = face.vertices;
    if (a == b || b == c || a == c ||
        IsDegenerateTriangle(positions[a], positions[b], positions[c])) {
      ++report.dropped_degenerate_triangles;
      continue;
    }
    std::array<VertexId, 3> key = face.vertices;
    std::sort(key.begin(), key.end());
    if (!seen.insert(key).second) {
      ++report.dropped_duplicate_triangles;
      continue;
    }
    kept.push_back(face);
  }
  if (kept.empty()) {
    return absl::InvalidArgumentError(
        absl::StrCat("no triangles left after cleaning (", report.dropped_degenerate_triangles,
                     " degenerate, ", report.dropped_duplicate_triangles, " duplicate dropped)"));
  }

  // 4. Keep the used vertices, numbered in file order.
  std::vector<VertexId> new_id(num_vertices, -1);
  for (const FaceInput& face : kept) {
    for (VertexId v : face.vertices) new_id[v] = 0;
  }
  MeshInput& mesh = out.mesh;
  for (VertexId v = 0; v < num_vertices; ++v) {
    if (new_id[v] < 0) {
      report.dropped_unreferenced_vertices += target[v] == v;
      continue;
    }
    new_id[v] = static_cast<VertexId>(mesh.positions.size());
    mesh.positions.push_back(positions[v]);
  }

  // 5. One material per name, in order of first use.
  std::unordered_map<std::string, MaterialId> material_by_name;
  std::vector<MaterialId> material_of_raw(raw.material_names.size(), -1);
  mesh.faces.reserve(kept.size());
  for (FaceInput face : kept) {
    for (VertexId& v : face.vertices) v = new_id[v];
    MaterialId& material = material_of_raw[face.material];
    if (material < 0) {
      const std::string& raw_name = raw.material_names[face.material];
      const std::string& name = raw_name.empty() ? options.default_material.name : raw_name;
      auto [it, inserted] =
          material_by_name.try_emplace(name, static_cast<MaterialId>(mesh.materials.size()));
      if (inserted) {
        Material m = options.default_material;
        m.name = name;
        mesh.materials.push_back(std::move(m));
      }
      material = it->second;
    }
    face.material = material;
    mesh.faces.push_back(face);
  }
  return out;
}

}  // namespace hs

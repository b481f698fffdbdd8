#pragma once
// From what a reader read to what HapticObject::Create accepts: validation,
// unit scale, welding, and dropping what cannot be touched. Internal to
// common/model. Messages do not name the file; ImportModel adds it.

#include <span>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "common/hds/haptic_object.h"
#include "common/model/import.h"
#include "common/model/raw_mesh.h"

namespace hs {

/// INVALID_ARGUMENT naming the first option out of its documented range
/// (unit_scale, weld_relative_tolerance, default_material).
absl::Status ValidateImportOptions(const ImportOptions& options);

/// INVALID_ARGUMENT when a coordinate is not finite, a polygon has fewer than
/// 3 corners or names a vertex out of range, a material index is out of
/// range, or the per-polygon arrays disagree in length.
absl::Status ValidateRawMesh(const RawMesh& mesh);

/// A mesh ready for HapticObject::Create and what cleaning did to get there.
struct CleanedMesh {
  MeshInput mesh;
  CleaningReport report;
};

/// Cleans `triangles` (cut from the polygons of `raw`, vertex indices into
/// raw.positions, materials into raw.material_names), in this order:
///  1. scales the positions by options.unit_scale (file unit -> metres);
///  2. welds each vertex into the earliest vertex within
///     weld_relative_tolerance times the diagonal of the box around the
///     vertices the triangles use (FindWeldTargets); the kept vertex keeps
///     its position;
///  3. drops the triangles that then repeat a vertex or have zero area
///     (IsDegenerateTriangle), then the triangles over the same three
///     vertices as an earlier kept one, whatever their order;
///  4. drops the vertices no kept triangle uses and numbers the rest densely,
///     in their file order;
///  5. makes one material per distinct name the kept triangles use, in order
///     of first use, each with the parameters of options.default_material
///     ("" becomes default_material.name).
/// Faces keep their file order, winding and source polygon.
/// Afterwards report.input_vertices == report.welded_vertices +
/// report.dropped_unreferenced_vertices + mesh.positions.size().
/// `raw` must pass ValidateRawMesh(). INVALID_ARGUMENT when a coordinate
/// overflows at the unit scale or no triangle is left ("no triangles").
absl::StatusOr<CleanedMesh> CleanMesh(const RawMesh& raw, std::span<const FaceInput> triangles,
                                      const ImportOptions& options);

}  // namespace hs

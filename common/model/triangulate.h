#pragma once
// Cutting the polygons of a model file into triangles. Internal to
// common/model.

#include <vector>

#include "common/hds/haptic_object.h"
#include "common/model/raw_mesh.h"

namespace hs {

/// Cuts every polygon of `mesh` into triangles over its own vertices: n - 2
/// triangles for an n-gon, concave polygons included (Coin's SbTesselator,
/// which clips ears in the polygon's best-fit plane). Each triangle keeps its
/// polygon's winding, material index (into mesh.material_names) and source
/// polygon id. The polygon is centred on its first vertex and projected in
/// float only to choose the triangles; the triangles name the original
/// vertices, so coordinates stay exact. Zero-area triangles may come out of
/// degenerate polygons; cleaning drops them. `mesh` must pass
/// ValidateRawMesh().
std::vector<FaceInput> TriangulatePolygons(const RawMesh& mesh);

}  // namespace hs

#include "common/model/triangulate.h"

#include <Inventor/SbTesselator.h>

#include <algorithm>
#include <cmath>

#include "common/model/coin_lock.h"

namespace hs {
namespace {

// Receives the tesselator's triangles. The tesselator hands back the data
// pointers given to addVertex: pointers into RawMesh::corners.
struct TesselatorSink {
  std::vector<FaceInput>* out = nullptr;
  MaterialId material = 0;
  PolygonId source_polygon = kNoPolygon;
  int emitted = 0;
};

void OnTriangle(void* v0, void* v1, void* v2, void* data) {
  auto* sink = static_cast<TesselatorSink*>(data);
  sink->out->push_back(
      FaceInput{{*static_cast<const int32_t*>(v0), *static_cast<const int32_t*>(v1),
                 *static_cast<const int32_t*>(v2)},
                sink->material,
                sink->source_polygon});
  ++sink->emitted;
}

void AddFan(std::span<const int32_t> corners, MaterialId material, PolygonId source_polygon,
            std::vector<FaceInput>& out) {
  for (size_t i = 1; i + 1 < corners.size(); ++i) {
    out.push_back(FaceInput{{corners[0], corners[i], corners[i + 1]}, material, source_polygon});
  }
}

}  // namespace

std::vector<FaceInput> TriangulatePolygons(const RawMesh& mesh) {
  std::vector<FaceInput> triangles;
  triangles.reserve(mesh.corners.size());
  TesselatorSink sink;
  sink.out = &triangles;
  // SbTesselator keeps no global state; Coin only has to be initialized.
  InitCoinOnce();
  SbTesselator tesselator(&OnTriangle, &sink);
  for (int p = 0; p < mesh.num_polygons(); ++p) {
    const std::span<const int32_t> corners = mesh.polygon(p);
    const int n = static_cast<int>(corners.size());
    const MaterialId material = mesh.polygon_materials[p];
    const PolygonId source_polygon = mesh.polygon_ids[p];
    if (n == 3) {
      AddFan(corners, material, source_polygon, triangles);
      continue;
    }
    // The polygon is centred on its first corner and scaled into [-1, 1] so
    // that float keeps its shape wherever it lies and whatever its size.
    const Vector3d& origin = mesh.positions[corners[0]];
    double extent = 0;
    for (int32_t corner : corners) {
      extent = std::max(extent, (mesh.positions[corner] - origin).cwiseAbs().maxCoeff());
    }
    if (!std::isfinite(extent)) {
      AddFan(corners, material, source_polygon, triangles);
      continue;
    }
    if (extent == 0) extent = 1;
    const size_t first = triangles.size();
    sink.material = material;
    sink.source_polygon = source_polygon;
    sink.emitted = 0;
    // keepVertices = TRUE: every corner ends up in a triangle, so a corner on
    // a straight stretch of the outline still meets the neighbouring
    // polygon's edges (no T-junction), and n - 2 triangles come out.
    tesselator.beginPolygon(TRUE);
    for (const int32_t& corner : corners) {
      const Vector3d local = (mesh.positions[corner] - origin) / extent;
      tesselator.addVertex(SbVec3f(static_cast<float>(local.x()), static_cast<float>(local.y()),
                                   static_cast<float>(local.z())),
                           const_cast<int32_t*>(&corner));
    }
    tesselator.endPolygon();
    if (sink.emitted != n - 2) {
      // Not seen with keepVertices = TRUE; should the tesselator ever give up
      // on a polygon, a fan keeps the triangle count and the provenance.
      triangles.resize(first);
      AddFan(corners, material, source_polygon, triangles);
    }
  }
  return triangles;
}

}  // namespace hs

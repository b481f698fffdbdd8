#include "common/model/procedural.h"

#include <cmath>
#include <map>
#include <numbers>

#include "common/core/check.h"

namespace hs {
namespace {

void AddQuad(MeshInput& mesh, VertexId a, VertexId b, VertexId c, VertexId d, PolygonId polygon) {
  mesh.faces.push_back(FaceInput{{a, b, c}, 0, polygon});
  mesh.faces.push_back(FaceInput{{a, c, d}, 0, polygon});
}

}  // namespace

MeshInput MakeBox(const Vector3d& size) {
  HS_CHECK((size.array() > 0).all());
  MeshInput mesh;
  mesh.materials.push_back(Material{});
  const Vector3d h = size / 2;
  for (int i = 0; i < 8; ++i) {
    mesh.positions.emplace_back(i & 1 ? h.x() : -h.x(), i & 2 ? h.y() : -h.y(),
                                i & 4 ? h.z() : -h.z());
  }
  // Vertex i has x from bit 0, y from bit 1, z from bit 2; each side listed
  // counter-clockwise seen from outside.
  AddQuad(mesh, 0, 2, 3, 1, 0);  // -z
  AddQuad(mesh, 4, 5, 7, 6, 1);  // +z
  AddQuad(mesh, 0, 1, 5, 4, 2);  // -y
  AddQuad(mesh, 2, 6, 7, 3, 3);  // +y
  AddQuad(mesh, 0, 4, 6, 2, 4);  // -x
  AddQuad(mesh, 1, 3, 7, 5, 5);  // +x
  return mesh;
}

MeshInput MakeIcosphere(double radius, int subdivisions) {
  HS_CHECK(radius > 0 && subdivisions >= 0);
  MeshInput mesh;
  mesh.materials.push_back(Material{});
  const double t = (1 + std::sqrt(5.0)) / 2;
  const double base[12][3] = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                              {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                              {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (const auto& p : base) mesh.positions.push_back(Vector3d(p[0], p[1], p[2]).normalized());
  std::vector<std::array<VertexId, 3>> faces = {
      {0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
      {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
      {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int s = 0; s < subdivisions; ++s) {
    std::map<std::pair<VertexId, VertexId>, VertexId> midpoint;
    auto mid = [&](VertexId a, VertexId b) {
      auto [it, inserted] = midpoint.try_emplace({std::min(a, b), std::max(a, b)}, 0);
      if (inserted) {
        it->second = static_cast<VertexId>(mesh.positions.size());
        mesh.positions.push_back((mesh.positions[a] + mesh.positions[b]).normalized());
      }
      return it->second;
    };
    std::vector<std::array<VertexId, 3>> finer;
    finer.reserve(faces.size() * 4);
    for (const auto& [a, b, c] : faces) {
      const VertexId ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
      finer.insert(finer.end(), {{a, ab, ca}, {b, bc, ab}, {c, ca, bc}, {ab, bc, ca}});
    }
    faces = std::move(finer);
  }
  for (Vector3d& p : mesh.positions) p *= radius;
  for (size_t f = 0; f < faces.size(); ++f) {
    mesh.faces.push_back(FaceInput{faces[f], 0, static_cast<PolygonId>(f)});
  }
  return mesh;
}

MeshInput MakeTorus(double major_radius, double minor_radius, int major_segments,
                    int minor_segments) {
  HS_CHECK(0 < minor_radius && minor_radius < major_radius);
  HS_CHECK(major_segments >= 3 && minor_segments >= 3);
  MeshInput mesh;
  mesh.materials.push_back(Material{});
  const double two_pi = 2 * std::numbers::pi;
  for (int i = 0; i < major_segments; ++i) {
    const double u = two_pi * i / major_segments;
    for (int j = 0; j < minor_segments; ++j) {
      const double v = two_pi * j / minor_segments;
      const double ring = major_radius + minor_radius * std::cos(v);
      mesh.positions.emplace_back(ring * std::cos(u), ring * std::sin(u),
                                  minor_radius * std::sin(v));
    }
  }
  auto id = [&](int i, int j) {
    return static_cast<VertexId>((i % major_segments) * minor_segments + j % minor_segments);
  };
  for (int i = 0; i < major_segments; ++i) {
    for (int j = 0; j < minor_segments; ++j) {
      AddQuad(mesh, id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1),
              static_cast<PolygonId>(i * minor_segments + j));
    }
  }
  return mesh;
}

MeshInput TransformMesh(MeshInput mesh, const Isometry3d& X) {
  for (Vector3d& p : mesh.positions) p = X * p;
  return mesh;
}

MeshInput MergeMeshes(MeshInput a, const MeshInput& b) {
  const auto vertex_offset = static_cast<VertexId>(a.positions.size());
  const auto material_offset = static_cast<MaterialId>(a.materials.size());
  PolygonId polygon_offset = 0;
  for (const FaceInput& f : a.faces)
    polygon_offset = std::max(polygon_offset, f.source_polygon + 1);
  a.positions.insert(a.positions.end(), b.positions.begin(), b.positions.end());
  a.materials.insert(a.materials.end(), b.materials.begin(), b.materials.end());
  for (FaceInput f : b.faces) {
    for (VertexId& v : f.vertices) v += vertex_offset;
    f.material += material_offset;
    if (f.source_polygon != kNoPolygon) f.source_polygon += polygon_offset;
    a.faces.push_back(f);
  }
  return a;
}

}  // namespace hs

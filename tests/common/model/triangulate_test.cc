#include "common/model/triangulate.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <set>
#include <vector>

namespace hs {
namespace {

constexpr double kPi = std::numbers::pi;

// A polygon's vector area (half the sum of its corners' cross products,
// taken from its first corner so that a tiny polygon far out keeps its
// digits): its normal times its area, for any simple polygon.
Vector3d VectorArea(const RawMesh& mesh, int p) {
  Vector3d sum = Vector3d::Zero();
  const auto corners = mesh.polygon(p);
  const Vector3d& origin = mesh.positions[corners[0]];
  for (size_t i = 1; i + 1 < corners.size(); ++i) {
    sum += (mesh.positions[corners[i]] - origin).cross(mesh.positions[corners[i + 1]] - origin);
  }
  return sum / 2;
}

Vector3d TriangleVectorArea(const RawMesh& mesh, const FaceInput& f) {
  const Vector3d &a = mesh.positions[f.vertices[0]], &b = mesh.positions[f.vertices[1]],
                 &c = mesh.positions[f.vertices[2]];
  return (b - a).cross(c - a) / 2;
}

// Adds a polygon over new vertices `outline` (a plane's x, y) placed by X.
void AddOutline(RawMesh& mesh, const std::vector<Eigen::Vector2d>& outline, const Isometry3d& X,
                int32_t material, PolygonId id) {
  std::vector<int32_t> corners;
  for (const Eigen::Vector2d& p : outline) {
    corners.push_back(static_cast<int32_t>(mesh.positions.size()));
    mesh.positions.push_back(X * Vector3d(p.x(), p.y(), 0));
  }
  mesh.AddPolygon(corners, material, id);
}

// The oracle for every polygon: n - 2 triangles over its own corners, each
// wound as the polygon (its area vector along the polygon's) with the
// polygon's material and id, tiling it: their areas add up to its area.
void ExpectTiles(const RawMesh& mesh, const std::vector<FaceInput>& triangles) {
  size_t next = 0;
  for (int p = 0; p < mesh.num_polygons(); ++p) {
    SCOPED_TRACE(p);
    const auto corners = mesh.polygon(p);
    const std::set<int32_t> own(corners.begin(), corners.end());
    const Vector3d area = VectorArea(mesh, p);
    Vector3d sum = Vector3d::Zero();
    std::set<int32_t> used;
    for (size_t k = 0; k + 2 < corners.size(); ++k, ++next) {
      ASSERT_LT(next, triangles.size());
      const FaceInput& f = triangles[next];
      EXPECT_EQ(f.material, mesh.polygon_materials[p]);
      EXPECT_EQ(f.source_polygon, mesh.polygon_ids[p]);
      for (VertexId v : f.vertices) {
        EXPECT_TRUE(own.count(v)) << v;
        used.insert(v);
      }
      const Vector3d t = TriangleVectorArea(mesh, f);
      EXPECT_GE(t.dot(area), -1e-12 * area.squaredNorm()) << "wound against its polygon";
      sum += t;
    }
    EXPECT_TRUE(sum.isApprox(area, 1e-9)) << sum.transpose() << " vs " << area.transpose();
    EXPECT_EQ(used, own) << "every corner is in a triangle";
  }
  EXPECT_EQ(next, triangles.size());
}

// Convex and concave outlines (an L, a comb, a star) in tilted planes,
// large and tiny, are cut into triangles that tile them.
TEST(TriangulateTest, ConcavePolygonsAreTiled) {
  using V = Eigen::Vector2d;
  const std::vector<std::vector<V>> outlines = {
      {V(0, 0), V(1, 0), V(1, 1)},
      {V(0, 0), V(2, 0), V(2, 1), V(0, 1)},
      {V(0, 0), V(2, 0), V(2, 1), V(1, 1), V(1, 3), V(0, 3)},  // L
      {V(0, 0), V(5, 0), V(5, 3), V(4, 3), V(4, 1), V(3, 1), V(3, 3), V(2, 3), V(2, 1), V(1, 1),
       V(1, 3), V(0, 3)},                             // comb
      {V(0, 0), V(1, 0), V(2, 0), V(2, 1), V(0, 1)},  // a corner on a straight side
  };
  RawMesh mesh;
  mesh.material_names = {"a", "b"};
  Isometry3d X = Isometry3d::Identity();
  X.rotate(Eigen::AngleAxisd(0.8, Vector3d(1, 2, 0.5).normalized()));
  X.translation() = Vector3d(1000, -20, 3);
  PolygonId id = 10;
  for (const double scale : {1.0, 1e-5, 300.0}) {
    for (const auto& outline : outlines) {
      std::vector<V> scaled;
      for (const V& p : outline) scaled.push_back(scale * p);
      AddOutline(mesh, scaled, X, id % 2, id);
      ++id;
    }
  }
  ExpectTiles(mesh, TriangulatePolygons(mesh));
}

// Random star-shaped outlines (corners at increasing angles, each in its
// own sector so that no gap reaches pi, at random radii), either way round,
// are tiled.
TEST(TriangulateTest, RandomStarPolygonsAreTiled) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> radius(0.2, 1.0), jitter(0, 0.8), angle(0, 2 * kPi);
  RawMesh mesh;
  mesh.material_names = {""};
  for (int k = 0; k < 100; ++k) {
    std::vector<double> angles(4 + k % 12);
    for (size_t i = 0; i < angles.size(); ++i) {
      angles[i] =
          2 * kPi * (static_cast<double>(i) + jitter(rng)) / static_cast<double>(angles.size());
    }
    std::vector<Eigen::Vector2d> outline;
    for (const double a : angles)
      outline.push_back(radius(rng) * Eigen::Vector2d(std::cos(a), std::sin(a)));
    if (k % 2) std::reverse(outline.begin(), outline.end());
    Isometry3d X = Isometry3d::Identity();
    X.rotate(Eigen::AngleAxisd(angle(rng), Vector3d(1, angle(rng), 2).normalized()));
    AddOutline(mesh, outline, X, 0, k);
  }
  ExpectTiles(mesh, TriangulatePolygons(mesh));
}

// Triangles stay triangles, corner for corner; polygons sharing vertices
// name the shared ones.
TEST(TriangulateTest, TrianglesAndSharedVerticesPassThrough) {
  RawMesh mesh;
  mesh.material_names = {""};
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}, {2, 1, 0}};
  mesh.AddPolygon(std::vector<int32_t>{2, 0, 1}, 0, 0);
  mesh.AddPolygon(std::vector<int32_t>{1, 4, 5, 2}, 0, 1);
  const std::vector<FaceInput> triangles = TriangulatePolygons(mesh);
  ASSERT_EQ(triangles.size(), 3u);
  EXPECT_EQ(triangles[0].vertices, (std::array<VertexId, 3>{2, 0, 1}));
  ExpectTiles(mesh, triangles);
}

}  // namespace
}  // namespace hs

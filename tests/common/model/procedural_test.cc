#include "common/model/procedural.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <utility>

namespace hs {
namespace {

constexpr double kPi = std::numbers::pi;

// The signed volume of a mesh (divergence theorem over its triangles):
// positive when the faces turn counter-clockwise seen from outside.
double SignedVolume(const MeshInput& mesh) {
  double six_volume = 0;
  for (const FaceInput& f : mesh.faces) {
    const Vector3d &a = mesh.positions[f.vertices[0]], &b = mesh.positions[f.vertices[1]],
                   &c = mesh.positions[f.vertices[2]];
    six_volume += a.dot(b.cross(c));
  }
  return six_volume / 6;
}

// Closed and consistently oriented: every directed edge appears once and
// its reverse once.
void ExpectClosedAndOriented(const MeshInput& mesh) {
  std::map<std::pair<VertexId, VertexId>, int> directed;
  for (const FaceInput& f : mesh.faces) {
    for (int i = 0; i < 3; ++i) ++directed[{f.vertices[i], f.vertices[(i + 1) % 3]}];
  }
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1) << edge.first << "->" << edge.second;
    EXPECT_EQ(directed.count({edge.second, edge.first}), 1u) << edge.first << "-" << edge.second;
  }
  EXPECT_TRUE(HapticObject::Create("mesh", mesh).ok());
}

// A box: 8 corners at the half sides, 12 faces, closed and outward, its
// volume the product of its sides, each side's two faces one polygon.
TEST(ProceduralTest, Box) {
  const Vector3d size(0.2, 0.4, 1.0);
  const MeshInput box = MakeBox(size);
  ASSERT_EQ(box.positions.size(), 8u);
  ASSERT_EQ(box.faces.size(), 12u);
  for (const Vector3d& p : box.positions) EXPECT_EQ(p.cwiseAbs(), size / 2);
  ExpectClosedAndOriented(box);
  EXPECT_NEAR(SignedVolume(box), size.prod(), 1e-15);
  std::map<PolygonId, std::set<int>> polygon_axes;
  for (const FaceInput& f : box.faces) {
    const Vector3d n = (box.positions[f.vertices[1]] - box.positions[f.vertices[0]])
                           .cross(box.positions[f.vertices[2]] - box.positions[f.vertices[0]]);
    int axis;
    n.cwiseAbs().maxCoeff(&axis);
    polygon_axes[f.source_polygon].insert(axis * 2 + (n[axis] > 0));
  }
  EXPECT_EQ(polygon_axes.size(), 6u);
  for (const auto& [polygon, sides] : polygon_axes) EXPECT_EQ(sides.size(), 1u) << polygon;
}

// An icosphere: 20 * 4^s faces, every vertex on the sphere, closed and
// outward, its volume below the ball's and nearing it as it is split.
TEST(ProceduralTest, Icosphere) {
  const double r = 0.3;
  double last_error = 1;
  for (int s = 0; s <= 3; ++s) {
    const MeshInput sphere = MakeIcosphere(r, s);
    ASSERT_EQ(sphere.faces.size(), 20u << (2 * s));
    // Euler: V - E + F = 2, with E = 3F/2.
    EXPECT_EQ(sphere.positions.size(), 2 + sphere.faces.size() / 2);
    for (const Vector3d& p : sphere.positions) EXPECT_NEAR(p.norm(), r, 1e-15);
    ExpectClosedAndOriented(sphere);
    const double ball = 4.0 / 3 * kPi * r * r * r;
    const double error = (ball - SignedVolume(sphere)) / ball;
    EXPECT_GT(error, 0) << s;
    EXPECT_LT(error, last_error) << s;
    last_error = error;
  }
  EXPECT_LT(last_error, 0.01);
}

// A torus: its M x m grid of quads, closed and outward, every vertex at the
// minor radius from the tube's centre circle, Euler characteristic 0, and
// its volume below 2 pi^2 R r^2, nearing it as the grid is refined.
TEST(ProceduralTest, Torus) {
  const double R = 1.0, r = 0.25;
  const MeshInput torus = MakeTorus(R, r, 48, 24);
  ASSERT_EQ(torus.positions.size(), 48u * 24u);
  ASSERT_EQ(torus.faces.size(), 2u * 48u * 24u);
  for (const Vector3d& p : torus.positions) {
    const double ring = std::hypot(p.x(), p.y());
    EXPECT_NEAR(std::hypot(ring - R, p.z()), r, 1e-12);
  }
  ExpectClosedAndOriented(torus);
  EXPECT_EQ(static_cast<int>(torus.positions.size()) -
                3 * static_cast<int>(torus.faces.size()) / 2 + static_cast<int>(torus.faces.size()),
            0);
  // Inscribed in the smooth torus, and closer to it at a finer grid.
  const double smooth = 2 * kPi * kPi * R * r * r;
  const double coarse = SignedVolume(torus), fine = SignedVolume(MakeTorus(R, r, 96, 48));
  EXPECT_LT(coarse, fine);
  EXPECT_LT(fine, smooth);
  EXPECT_GT(coarse, 0.98 * smooth);
  std::map<PolygonId, int> faces_per_polygon;
  for (const FaceInput& f : torus.faces) ++faces_per_polygon[f.source_polygon];
  EXPECT_EQ(faces_per_polygon.size(), 48u * 24u);
  for (const auto& [polygon, count] : faces_per_polygon) EXPECT_EQ(count, 2) << polygon;
}

// TransformMesh moves every vertex by X and keeps the faces.
TEST(ProceduralTest, TransformMovesEveryVertex) {
  Isometry3d X = Isometry3d::Identity();
  X.translate(Vector3d(1, -2, 3)).rotate(Eigen::AngleAxisd(0.7, Vector3d(1, 2, 3).normalized()));
  const MeshInput box = MakeBox(Vector3d(1, 2, 3));
  const MeshInput moved = TransformMesh(box, X);
  ASSERT_EQ(moved.positions.size(), box.positions.size());
  for (size_t i = 0; i < box.positions.size(); ++i) {
    EXPECT_TRUE(moved.positions[i].isApprox(X * box.positions[i]));
  }
  for (size_t f = 0; f < box.faces.size(); ++f) {
    EXPECT_EQ(moved.faces[f].vertices, box.faces[f].vertices);
  }
  EXPECT_NEAR(SignedVolume(moved), 6, 1e-12);  // a rigid motion keeps volume and orientation
}

// MergeMeshes keeps both meshes whole: b's vertex, material and polygon ids
// come after a's, and the volumes add up.
TEST(ProceduralTest, MergeShiftsTheSecondMeshsIds) {
  MeshInput b = TransformMesh(MakeBox(Vector3d::Ones()), Isometry3d(Eigen::Translation3d(5, 0, 0)));
  b.materials[0].name = "second";
  const MeshInput a = MakeBox(Vector3d(1, 2, 3));
  const MeshInput merged = MergeMeshes(a, b);
  ASSERT_EQ(merged.positions.size(), 16u);
  ASSERT_EQ(merged.faces.size(), 24u);
  ASSERT_EQ(merged.materials.size(), 2u);
  EXPECT_EQ(merged.materials[1].name, "second");
  for (size_t f = 0; f < 12; ++f) {
    const FaceInput &got = merged.faces[12 + f], &want = b.faces[f];
    for (int i = 0; i < 3; ++i) EXPECT_EQ(got.vertices[i], want.vertices[i] + 8);
    EXPECT_EQ(got.material, 1);
    EXPECT_EQ(got.source_polygon, want.source_polygon + 6);  // a's polygons are 0..5
  }
  ExpectClosedAndOriented(merged);
  EXPECT_NEAR(SignedVolume(merged), 6 + 1, 1e-12);
}

}  // namespace
}  // namespace hs

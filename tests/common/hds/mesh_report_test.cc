#include "common/hds/mesh_report.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/model/procedural.h"

namespace hs {
namespace {

using ::testing::ElementsAre;

MeshReport Inspect(MeshInput mesh) {
  auto object = HapticObject::Create("test", std::move(mesh));
  EXPECT_TRUE(object.ok()) << object.status();
  return InspectMesh(*object);
}

// A box without its top side is open: the four edges around the hole are
// boundary edges, and V - E + F drops to 1 (a disc).
TEST(MeshReportTest, OpenBoxHasBoundary) {
  MeshInput mesh = MakeBox(Vector3d(1, 1, 1));
  mesh.faces.erase(mesh.faces.begin() + 2, mesh.faces.begin() + 4);  // +z side
  const MeshReport report = Inspect(mesh);
  EXPECT_FALSE(report.closed);
  EXPECT_EQ(report.boundary_edges, 4);
  EXPECT_EQ(report.non_manifold_edges, 0);
  EXPECT_EQ(report.euler_characteristic, 1);
  EXPECT_TRUE(report.consistently_oriented);
}

// Three triangles on one edge make it non-manifold, and the mesh not closed.
TEST(MeshReportTest, NonManifoldEdge) {
  MeshInput mesh;
  mesh.materials.emplace_back();
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
  mesh.faces = {{{0, 1, 2}}, {{1, 0, 3}}, {{0, 1, 4}}};
  const MeshReport report = Inspect(mesh);
  EXPECT_EQ(report.non_manifold_edges, 1);
  EXPECT_EQ(report.boundary_edges, 6);
  EXPECT_FALSE(report.closed);
}

// A face whose vertices are collinear is reported degenerate, at any scale.
TEST(MeshReportTest, DegenerateFaceAtEveryScale) {
  for (double scale : {1e-4, 1.0, 1e4}) {
    SCOPED_TRACE(scale);
    MeshInput mesh;
    mesh.materials.emplace_back();
    mesh.positions = {{0, 0, 0}, {scale, 0, 0}, {2 * scale, 0, 0}, {0, scale, 0}};
    mesh.faces = {{{0, 1, 2}}, {{0, 1, 3}}};
    EXPECT_THAT(Inspect(mesh).degenerate_faces, ElementsAre(0));
  }
}

// A sliver that is thin but not flat (height 1e-6 of its length) is not degenerate.
TEST(MeshReportTest, SliverIsNotDegenerate) {
  MeshInput mesh;
  mesh.materials.emplace_back();
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0.5, 1e-6, 0}};
  mesh.faces = {{{0, 1, 2}}};
  EXPECT_TRUE(Inspect(mesh).degenerate_faces.empty());
}

// Two vertices at one position (a seam) count as one duplicate; a vertex no
// face uses is counted as unreferenced.
TEST(MeshReportTest, DuplicateAndUnreferencedVertices) {
  MeshInput mesh = MakeBox(Vector3d(1, 1, 1));
  mesh.positions.push_back(mesh.positions[0]);
  mesh.faces[0].vertices[0] = 8;  // the seam: face 0 now uses the copy
  mesh.positions.emplace_back(5, 5, 5);
  const MeshReport report = Inspect(mesh);
  EXPECT_EQ(report.duplicate_vertices, 1);
  EXPECT_EQ(report.unreferenced_vertices, 1);
  EXPECT_FALSE(report.closed);  // the seam opens the mesh topologically
}

// Flipping one face of a closed box breaks consistent orientation only.
TEST(MeshReportTest, FlippedFaceBreaksOrientation) {
  MeshInput mesh = MakeBox(Vector3d(1, 1, 1));
  std::swap(mesh.faces[5].vertices[0], mesh.faces[5].vertices[1]);
  const MeshReport report = Inspect(mesh);
  EXPECT_TRUE(report.closed);
  EXPECT_FALSE(report.consistently_oriented);
}

}  // namespace
}  // namespace hs

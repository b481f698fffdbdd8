#include "common/hds/haptic_object.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>

#include "common/hds/mesh_report.h"
#include "common/model/procedural.h"

namespace hs {
namespace {

using ::testing::Contains;
using ::testing::ElementsAre;

HapticObject Build(MeshInput mesh) {
  auto object = HapticObject::Create("test", std::move(mesh));
  EXPECT_TRUE(object.ok()) << object.status();
  return *std::move(object);
}

MeshInput TwoLinkedTori() {
  // The second torus stands in the xz plane through the hole of the first.
  Isometry3d X = Isometry3d::Identity();
  X.translate(Vector3d(1.0, 0, 0));
  X.rotate(Eigen::AngleAxisd(M_PI / 2, Vector3d::UnitX()));
  return MergeMeshes(MakeTorus(1.0, 0.25, 24, 12), TransformMesh(MakeTorus(1.0, 0.25, 24, 12), X));
}

// Every face lists its edges, every edge lists that face back, and the same
// holds between vertices and faces and between vertices and edges.
void ExpectAdjacencySymmetric(const HapticObject& o) {
  for (FaceId f = 0; f < o.num_faces(); ++f) {
    const Face& face = o.face(f);
    for (int i = 0; i < 3; ++i) {
      const EdgeId e = face.edges[i];
      EXPECT_THAT(o.EdgeFaces(e), Contains(f));
      EXPECT_THAT(o.VertexFaces(face.vertices[i]), Contains(f));
      const VertexId a = std::min(face.vertices[i], face.vertices[(i + 1) % 3]);
      const VertexId b = std::max(face.vertices[i], face.vertices[(i + 1) % 3]);
      EXPECT_THAT(o.edge(e).vertices, ElementsAre(a, b));
      EXPECT_EQ(o.FindEdge(a, b), e);
      EXPECT_EQ(o.FindEdge(b, a), e);
    }
  }
  for (EdgeId e = 0; e < o.num_edges(); ++e) {
    for (FaceId f : o.EdgeFaces(e)) EXPECT_THAT(o.face(f).edges, Contains(e));
    for (VertexId v : o.edge(e).vertices) EXPECT_THAT(o.VertexEdges(v), Contains(e));
  }
  for (VertexId v = 0; v < o.num_vertices(); ++v) {
    for (FaceId f : o.VertexFaces(v)) EXPECT_THAT(o.face(f).vertices, Contains(v));
    for (EdgeId e : o.VertexEdges(v)) EXPECT_THAT(o.edge(e).vertices, Contains(v));
  }
}

struct ClosedShape {
  const char* name;
  MeshInput mesh;
  int euler_characteristic;
  int components;
};

std::vector<ClosedShape> ClosedShapes() {
  return {{"box", MakeBox(Vector3d(1, 2, 3)), 2, 1},
          {"icosphere0", MakeIcosphere(1.0, 0), 2, 1},
          {"icosphere3", MakeIcosphere(0.5, 3), 2, 1},
          {"torus", MakeTorus(1.0, 0.3, 16, 8), 0, 1},
          {"linked_tori", TwoLinkedTori(), 0, 2}};
}

// Closed procedural shapes have the Euler characteristic of their topology
// (2 per sphere, 0 per torus), two faces per edge, and symmetric adjacency.
TEST(HapticObjectTest, ClosedShapesHaveTheirTopology) {
  for (ClosedShape& shape : ClosedShapes()) {
    SCOPED_TRACE(shape.name);
    const HapticObject o = Build(shape.mesh);
    const MeshReport report = InspectMesh(o);
    EXPECT_EQ(report.euler_characteristic, shape.euler_characteristic);
    EXPECT_EQ(report.connected_components, shape.components);
    EXPECT_TRUE(report.closed);
    EXPECT_TRUE(report.consistently_oriented);
    EXPECT_EQ(report.boundary_edges, 0);
    EXPECT_EQ(report.non_manifold_edges, 0);
    EXPECT_TRUE(report.degenerate_faces.empty());
    EXPECT_EQ(report.duplicate_vertices, 0);
    EXPECT_EQ(2 * o.num_edges(), 3 * o.num_faces());
    for (EdgeId e = 0; e < o.num_edges(); ++e) EXPECT_EQ(o.EdgeFaces(e).size(), 2u);
    ExpectAdjacencySymmetric(o);
  }
}

// The outward orientation of the procedural shapes gives a positive signed
// volume equal to the analytic one (exact for the box).
TEST(HapticObjectTest, BoxVolumeAndBoundingBox) {
  const HapticObject o = Build(MakeBox(Vector3d(1, 2, 3)));
  double volume = 0;
  for (const Face& f : o.faces()) {
    volume +=
        o.position(f.vertices[0]).dot(o.position(f.vertices[1]).cross(o.position(f.vertices[2]))) /
        6;
  }
  EXPECT_DOUBLE_EQ(volume, 6.0);
  EXPECT_TRUE(o.bounding_box().min().isApprox(Vector3d(-0.5, -1, -1.5)));
  EXPECT_TRUE(o.bounding_box().max().isApprox(Vector3d(0.5, 1, 1.5)));
  EXPECT_DOUBLE_EQ(o.smallest_box_edge(), 1.0);
}

// Moving vertices changes only their positions, bumps the geometry version,
// keeps the topology, and is reported exactly by the change queries.
TEST(HapticObjectTest, MoveVerticesKeepsTopologyAndReportsChanges) {
  HapticObject o = Build(MakeIcosphere(1.0, 2));
  const HapticObject before = o;
  const uint64_t v0 = o.geometry_version();
  const std::vector<VertexId> ids = {3, 17};
  const std::vector<Vector3d> to = {Vector3d(2, 0, 0), Vector3d(0, 0, -3)};
  ASSERT_TRUE(o.MoveVertices(ids, to).ok());
  EXPECT_EQ(o.geometry_version(), v0 + 1);
  EXPECT_EQ(o.position(3), to[0]);
  EXPECT_EQ(o.position(17), to[1]);
  EXPECT_THAT(o.VerticesChangedSince(v0), ElementsAre(3, 17));
  EXPECT_TRUE(o.VerticesChangedSince(v0 + 1).empty());
  std::vector<FaceId> expected_faces;
  for (VertexId v : ids) {
    for (FaceId f : o.VertexFaces(v)) expected_faces.push_back(f);
  }
  std::sort(expected_faces.begin(), expected_faces.end());
  expected_faces.erase(std::unique(expected_faces.begin(), expected_faces.end()),
                       expected_faces.end());
  EXPECT_EQ(o.FacesChangedSince(v0), expected_faces);
  EXPECT_DOUBLE_EQ(o.bounding_box().max().x(), 2.0);
  EXPECT_DOUBLE_EQ(o.bounding_box().min().z(), -3.0);
  for (FaceId f = 0; f < o.num_faces(); ++f) {
    EXPECT_EQ(o.face(f).vertices, before.face(f).vertices);
    EXPECT_EQ(o.face(f).edges, before.face(f).edges);
  }
  ExpectAdjacencySymmetric(o);
  EXPECT_EQ(InspectMesh(o).euler_characteristic, 2);
}

// A rejected modification leaves positions, versions and materials as they were.
TEST(HapticObjectTest, RejectedModificationChangesNothing) {
  HapticObject o = Build(MakeBox(Vector3d(1, 1, 1)));
  const std::vector<Vector3d> positions(o.positions().begin(), o.positions().end());
  const uint64_t version = o.geometry_version();
  const std::vector<VertexId> ids = {0, 99};
  const std::vector<Vector3d> to = {Vector3d(5, 5, 5), Vector3d(0, 0, 0)};
  EXPECT_EQ(o.MoveVertices(ids, to).code(), absl::StatusCode::kInvalidArgument);
  const std::vector<VertexId> one = {0};
  const std::vector<Vector3d> nan = {Vector3d(std::numeric_limits<double>::quiet_NaN(), 0, 0)};
  EXPECT_EQ(o.MoveVertices(one, nan).code(), absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(o.MoveVertices(one, to).code(), absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(o.SetFaceMaterial(12, 0).code(), absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(o.SetFaceMaterial(0, 1).code(), absl::StatusCode::kInvalidArgument);
  Material bad;
  bad.stiffness_n_per_m = -1;
  EXPECT_EQ(o.SetMaterial(0, bad).code(), absl::StatusCode::kInvalidArgument);
  EXPECT_TRUE(std::equal(positions.begin(), positions.end(), o.positions().begin()));
  EXPECT_EQ(o.geometry_version(), version);
  EXPECT_EQ(o.material_version(), 1u);
  EXPECT_EQ(o.materials()[0], Material{});
}

// Face materials can change and the change is versioned apart from geometry.
TEST(HapticObjectTest, FaceMaterialChanges) {
  MeshInput mesh = MakeBox(Vector3d(1, 1, 1));
  mesh.materials.push_back(Material{.name = "bone", .stiffness_n_per_m = 5000});
  HapticObject o = Build(mesh);
  ASSERT_TRUE(o.SetFaceMaterial(4, 1).ok());
  EXPECT_EQ(o.face_material(4).name, "bone");
  EXPECT_EQ(o.face_material(5).name, "default");
  EXPECT_EQ(o.material_version(), 2u);
  EXPECT_EQ(o.geometry_version(), 1u);
}

// Create rejects meshes it cannot hold, each with INVALID_ARGUMENT.
TEST(HapticObjectTest, CreateRejectsInvalidMeshes) {
  auto expect_invalid = [](MeshInput mesh, const char* why) {
    SCOPED_TRACE(why);
    EXPECT_EQ(HapticObject::Create("bad", std::move(mesh)).status().code(),
              absl::StatusCode::kInvalidArgument);
  };
  MeshInput nan = MakeBox(Vector3d(1, 1, 1));
  nan.positions[2].y() = std::numeric_limits<double>::quiet_NaN();
  expect_invalid(nan, "NaN coordinate");
  MeshInput inf = MakeBox(Vector3d(1, 1, 1));
  inf.positions[0].z() = std::numeric_limits<double>::infinity();
  expect_invalid(inf, "infinite coordinate");
  MeshInput out_of_range = MakeBox(Vector3d(1, 1, 1));
  out_of_range.faces[3].vertices[1] = 8;
  expect_invalid(out_of_range, "vertex index out of range");
  MeshInput negative = MakeBox(Vector3d(1, 1, 1));
  negative.faces[0].vertices[0] = -1;
  expect_invalid(negative, "negative vertex index");
  MeshInput repeated = MakeBox(Vector3d(1, 1, 1));
  repeated.faces[0].vertices[1] = repeated.faces[0].vertices[0];
  expect_invalid(repeated, "repeated vertex");
  MeshInput bad_material = MakeBox(Vector3d(1, 1, 1));
  bad_material.faces[0].material = 1;
  expect_invalid(bad_material, "material index out of range");
  MeshInput bad_friction = MakeBox(Vector3d(1, 1, 1));
  bad_friction.materials[0].dynamic_friction = 2 * bad_friction.materials[0].static_friction;
  expect_invalid(bad_friction, "dynamic friction above static");
  MeshInput empty = MakeBox(Vector3d(1, 1, 1));
  empty.faces.clear();
  expect_invalid(empty, "no faces");
}

}  // namespace
}  // namespace hs

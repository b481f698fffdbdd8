#include "common/model/assimp_reader.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

#include "tests/common/model/reader_oracle.h"
#include "tests/common/test_data_dir.h"

namespace hs {
namespace {

using testing_raw_mesh::DataBytes;
using testing_raw_mesh::MaterialName;
using testing_raw_mesh::Side;
using testing_raw_mesh::SignedVolume;
using testing_raw_mesh::UsedBox;

// cube.obj's six quads stay quads, numbered in file order, each with the
// material the file gives its side (steel: -z, +z, -y; rubber: +y, -x,
// +x), enclosing the unit cube outward.
TEST(AssimpReaderTest, ObjQuadsWithMaterials) {
  const absl::StatusOr<RawMesh> mesh = ReadWithAssimp(TestDataPath("cube.obj"));
  ASSERT_TRUE(mesh.ok()) << mesh.status();
  ASSERT_EQ(mesh->num_polygons(), 6);
  const std::set<std::string> steel = {"-z", "+z", "-y"};
  for (int p = 0; p < 6; ++p) {
    EXPECT_EQ(mesh->polygon(p).size(), 4u);
    EXPECT_EQ(mesh->polygon_ids[p], p);
    EXPECT_EQ(MaterialName(*mesh, p), steel.count(Side(*mesh, p)) ? "steel" : "rubber")
        << Side(*mesh, p);
  }
  EXPECT_NEAR(SignedVolume(*mesh), 1, 1e-12);
  EXPECT_TRUE(UsedBox(*mesh).isApprox(AlignedBox3d(Vector3d::Zero(), Vector3d::Ones())));
}

// From bytes alone the same polygons come out as from the file; the
// material library it names is not opened.
TEST(AssimpReaderTest, BytesReadAsTheFile) {
  const absl::StatusOr<RawMesh> file = ReadWithAssimp(TestDataPath("cube.obj"));
  const absl::StatusOr<RawMesh> bytes = ReadBytesWithAssimp(DataBytes("cube.obj"), "cube.obj");
  ASSERT_TRUE(file.ok() && bytes.ok()) << bytes.status();
  ASSERT_EQ(bytes->num_polygons(), file->num_polygons());
  for (int p = 0; p < file->num_polygons(); ++p) {
    ASSERT_EQ(bytes->polygon(p).size(), file->polygon(p).size());
    for (size_t i = 0; i < file->polygon(p).size(); ++i) {
      EXPECT_EQ(bytes->positions[bytes->polygon(p)[i]], file->positions[file->polygon(p)[i]]);
    }
  }
}

// COLLADA: one cube in two nodes gives two copies, the node transforms
// applied (the second scaled 2, moved 2 in x) and the file's Z_UP ignored.
TEST(AssimpReaderTest, ColladaInstancesAreCopiesInFileCoordinates) {
  const absl::StatusOr<RawMesh> mesh = ReadWithAssimp(TestDataPath("two_cubes.dae"));
  ASSERT_TRUE(mesh.ok()) << mesh.status();
  EXPECT_NEAR(SignedVolume(*mesh), 1 + 8, 1e-9);
  EXPECT_TRUE(UsedBox(*mesh).isApprox(AlignedBox3d(Vector3d::Zero(), Vector3d(4, 2, 2)), 1e-9))
      << UsedBox(*mesh).min().transpose() << " / " << UsedBox(*mesh).max().transpose();
  std::set<PolygonId> ids(mesh->polygon_ids.begin(), mesh->polygon_ids.end());
  EXPECT_EQ(ids.size(), static_cast<size_t>(mesh->num_polygons()));
}

// DXF: the turn assimp puts on DXF scenes is taken off, so the cube stays
// where the file has it.
TEST(AssimpReaderTest, DxfKeepsFileCoordinates) {
  const absl::StatusOr<RawMesh> mesh = ReadWithAssimp(TestDataPath("cube.dxf"));
  ASSERT_TRUE(mesh.ok()) << mesh.status();
  EXPECT_EQ(mesh->num_polygons(), 6);
  EXPECT_TRUE(UsedBox(*mesh).isApprox(AlignedBox3d(Vector3d::Zero(), Vector3d::Ones()), 1e-9));
  EXPECT_NEAR(std::abs(SignedVolume(*mesh)), 1, 1e-9);
}

// Points and lines are no polygons: a file of nothing else gives none, and
// what comes next decides that no triangles is an error.
TEST(AssimpReaderTest, PointsAndLinesAreSkipped) {
  const absl::StatusOr<RawMesh> mesh = ReadWithAssimp(TestDataPath("lines_only.obj"));
  ASSERT_TRUE(mesh.ok()) << mesh.status();
  EXPECT_EQ(mesh->num_polygons(), 0);
}

// An OBJ of random bytes, which assimp takes for a scene without meshes, is
// refused here as having no triangles.
TEST(AssimpReaderTest, SceneWithoutMeshesIsInvalidArgument) {
  const absl::Status status = ReadWithAssimp(TestDataPath("garbage.obj")).status();
  EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(status.message().find("no triangles"), std::string::npos) << status;
}

// What assimp cannot read is INVALID_ARGUMENT, never an exception.
TEST(AssimpReaderTest, UnreadableFilesAreInvalidArgument) {
  for (const char* name : {"garbage.stl", "truncated_binary.stl", "no_such.obj"}) {
    EXPECT_EQ(ReadWithAssimp(TestDataPath(name)).status().code(),
              absl::StatusCode::kInvalidArgument)
        << name;
  }
  EXPECT_EQ(ReadBytesWithAssimp(DataBytes("garbage.stl"), "garbage.stl").status().code(),
            absl::StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace hs

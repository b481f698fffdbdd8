#include "common/model/coin_reader.h"

#include <gtest/gtest.h>

#include <map>
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

// Checks a unit cube read by Coin: triangles, two per side sharing a
// polygon id (one id per side, dense from 0), the side's material by
// `material_of`, and the cube enclosed outward.
void ExpectCube(const RawMesh& mesh, const std::map<std::string, std::string>& material_of) {
  ASSERT_EQ(mesh.num_polygons(), 12);
  std::map<PolygonId, std::set<std::string>> sides_of_id;
  for (int p = 0; p < mesh.num_polygons(); ++p) {
    EXPECT_EQ(mesh.polygon(p).size(), 3u);
    sides_of_id[mesh.polygon_ids[p]].insert(Side(mesh, p));
    EXPECT_EQ(MaterialName(mesh, p), material_of.at(Side(mesh, p))) << Side(mesh, p);
  }
  ASSERT_EQ(sides_of_id.size(), 6u);
  EXPECT_EQ(sides_of_id.begin()->first, 0);
  EXPECT_EQ(sides_of_id.rbegin()->first, 5);
  for (const auto& [id, sides] : sides_of_id) EXPECT_EQ(sides.size(), 1u) << id;
  EXPECT_NEAR(SignedVolume(mesh), 1, 1e-12);
}

const std::map<std::string, std::string> kSteelAndRubber = {{"-z", "steel"},  {"+z", "steel"},
                                                            {"-y", "steel"},  {"+y", "rubber"},
                                                            {"-x", "rubber"}, {"+x", "rubber"}};

// Inventor: each face's triangles share its id; the DEF names of the
// Material nodes name the materials.
TEST(CoinReaderTest, InventorFacesAndMaterials) {
  const absl::StatusOr<RawMesh> mesh = ReadWithCoin(TestDataPath("cube.iv"));
  ASSERT_TRUE(mesh.ok()) << mesh.status();
  ExpectCube(*mesh, kSteelAndRubber);
}

// VRML 2: two shapes over one Coordinate, named materials.
TEST(CoinReaderTest, Vrml2Shapes) {
  const absl::StatusOr<RawMesh> mesh = ReadWithCoin(TestDataPath("cube.wrl"));
  ASSERT_TRUE(mesh.ok()) << mesh.status();
  ExpectCube(*mesh, kSteelAndRubber);
}

// VRML 1: one Material node of two values bound per face gives the node's
// name with each value's index.
TEST(CoinReaderTest, MaterialValuesBoundPerFace) {
  const absl::StatusOr<RawMesh> mesh = ReadWithCoin(TestDataPath("cube_vrml1.wrl"));
  ASSERT_TRUE(mesh.ok()) << mesh.status();
  ExpectCube(*mesh, {{"-z", "paint_0"},
                     {"+z", "paint_0"},
                     {"-y", "paint_0"},
                     {"+y", "paint_1"},
                     {"-x", "paint_1"},
                     {"+x", "paint_1"}});
}

// Clockwise faces under a mirroring transform face outward once both are
// honoured, in the transformed place.
TEST(CoinReaderTest, MirrorAndClockwiseStillFaceOutward) {
  const absl::StatusOr<RawMesh> mesh = ReadWithCoin(TestDataPath("cube_mirrored.wrl"));
  ASSERT_TRUE(mesh.ok()) << mesh.status();
  EXPECT_NEAR(SignedVolume(*mesh), 1, 1e-12);
  EXPECT_TRUE(UsedBox(*mesh).isApprox(AlignedBox3d(Vector3d(2, 0, -1), Vector3d(3, 1, 0)), 1e-12));
}

// From bytes, the same mesh as from the file.
TEST(CoinReaderTest, BytesReadAsTheFile) {
  const absl::StatusOr<RawMesh> file = ReadWithCoin(TestDataPath("cube.iv"));
  const absl::StatusOr<RawMesh> bytes = ReadBytesWithCoin(DataBytes("cube.iv"));
  ASSERT_TRUE(file.ok() && bytes.ok()) << bytes.status();
  EXPECT_EQ(bytes->positions, file->positions);
  EXPECT_EQ(bytes->corners, file->corners);
  EXPECT_EQ(bytes->polygon_ids, file->polygon_ids);
  EXPECT_EQ(bytes->material_names, file->material_names);
}

// Files Coin cannot parse, and indices out of range (which Coin would walk
// unchecked), are INVALID_ARGUMENT saying why; Coin prints nothing.
TEST(CoinReaderTest, BadFilesAreInvalidArgumentAndQuiet) {
  const std::map<std::string, std::string> bad = {{"garbage.iv", "Not a valid Inventor file"},
                                                  {"truncated.iv", "got EOF"},
                                                  {"bad_index.iv", "coordIndex[2] = 9"}};
  for (const auto& [name, reason] : bad) {
    testing::internal::CaptureStderr();
    const absl::StatusOr<RawMesh> mesh = ReadWithCoin(TestDataPath(name));
    const std::string printed = testing::internal::GetCapturedStderr();
    EXPECT_EQ(mesh.status().code(), absl::StatusCode::kInvalidArgument) << name;
    EXPECT_NE(mesh.status().message().find(reason), std::string::npos) << mesh.status();
    EXPECT_EQ(printed, "") << name;
    EXPECT_EQ(ReadBytesWithCoin(DataBytes(name)).status().code(),
              absl::StatusCode::kInvalidArgument)
        << name;
  }
}

}  // namespace
}  // namespace hs

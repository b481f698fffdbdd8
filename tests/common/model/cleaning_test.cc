#include "common/model/cleaning.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace hs {
namespace {

FaceInput Triangle(VertexId a, VertexId b, VertexId c, MaterialId material, PolygonId polygon) {
  return FaceInput{{a, b, c}, material, polygon};
}

// A 1 m square in millimetres, cut by hand into what cleaning must sort
// out. Vertices: 0-3 the square's corners; 4 a copy of corner 2 lifted by
// 1e-7 mm (1e-10 m, far under the weld tolerance 1e-6 x 1.41 m); 5 far away
// and unused; 6 the midpoint of edge 0-1.
RawMesh SquareWithFaults() {
  RawMesh raw;
  raw.positions = {{0, 0, 0},          {1000, 0, 0},       {1000, 1000, 0}, {0, 1000, 0},
                   {1000, 1000, 1e-7}, {5000, 5000, 5000}, {500, 0, 0}};
  raw.material_names = {"", "steel"};
  const int32_t square[] = {0, 1, 2, 3};
  raw.AddPolygon(square, 0, 0);
  for (PolygonId id = 1; id <= 3; ++id) {
    const int32_t triangle[] = {0, 6, 1};  // shapes do not matter to the counts
    raw.AddPolygon(triangle, 1, id);
  }
  return raw;
}

// Each kind of fault is counted once, by hand: vertex 4 welds into 2; the
// triangle (3, 0, 4) becomes (3, 0, 2), the vertices of (0, 2, 3): a
// duplicate; (0, 6, 1) has zero area and (1, 2, 4) collapses to (1, 2, 2):
// degenerate; vertices 5 and 6 end up unused. What is left is the square's
// two triangles over vertices 0-3, in metres, in file order, their
// materials made in order of first use, "" named after the default.
TEST(CleaningTest, EachFaultCountedByHand) {
  const RawMesh raw = SquareWithFaults();
  const std::vector<FaceInput> triangles = {Triangle(0, 1, 2, 1, 0), Triangle(0, 2, 3, 0, 0),
                                            Triangle(3, 0, 4, 0, 1), Triangle(0, 6, 1, 1, 2),
                                            Triangle(1, 2, 4, 1, 3)};
  ImportOptions options;
  options.unit_scale = 0.001;
  options.default_material.name = "tissue";
  options.default_material.stiffness_n_per_m = 321;
  const absl::StatusOr<CleanedMesh> cleaned = CleanMesh(raw, triangles, options);
  ASSERT_TRUE(cleaned.ok()) << cleaned.status();
  const CleaningReport& report = cleaned->report;
  EXPECT_EQ(report.input_vertices, 7);
  EXPECT_EQ(report.input_polygons, 4);
  EXPECT_EQ(report.input_triangles, 5);
  EXPECT_EQ(report.welded_vertices, 1);
  EXPECT_EQ(report.dropped_duplicate_triangles, 1);
  EXPECT_EQ(report.dropped_degenerate_triangles, 2);
  EXPECT_EQ(report.dropped_unreferenced_vertices, 2);
  const MeshInput& mesh = cleaned->mesh;
  ASSERT_EQ(mesh.positions.size(), 4u);
  EXPECT_EQ(report.input_vertices, report.welded_vertices + report.dropped_unreferenced_vertices +
                                       static_cast<int>(mesh.positions.size()));
  EXPECT_EQ(mesh.positions[1], Vector3d(1, 0, 0));
  EXPECT_EQ(mesh.positions[2], Vector3d(1, 1, 0));  // the kept vertex keeps its position
  ASSERT_EQ(mesh.faces.size(), 2u);
  EXPECT_EQ(mesh.faces[0].vertices, (std::array<VertexId, 3>{0, 1, 2}));
  EXPECT_EQ(mesh.faces[1].vertices, (std::array<VertexId, 3>{0, 2, 3}));
  EXPECT_EQ(mesh.faces[0].source_polygon, 0);
  ASSERT_EQ(mesh.materials.size(), 2u);
  EXPECT_EQ(mesh.faces[0].material, 0);
  EXPECT_EQ(mesh.materials[0].name, "steel");
  EXPECT_EQ(mesh.faces[1].material, 1);
  EXPECT_EQ(mesh.materials[1].name, "tissue");
  for (const Material& m : mesh.materials) EXPECT_EQ(m.stiffness_n_per_m, 321);
}

// A weld tolerance of 0 merges exact copies only: vertex 4 stays, so
// (1, 2, 4) is a sliver of zero area (still degenerate) and (3, 0, 4) a
// triangle of its own.
TEST(CleaningTest, ZeroToleranceWeldsExactCopiesOnly) {
  const RawMesh raw = SquareWithFaults();
  const std::vector<FaceInput> triangles = {Triangle(0, 2, 3, 0, 0), Triangle(3, 0, 4, 0, 1)};
  ImportOptions options;
  options.weld_relative_tolerance = 0;
  const absl::StatusOr<CleanedMesh> cleaned = CleanMesh(raw, triangles, options);
  ASSERT_TRUE(cleaned.ok()) << cleaned.status();
  EXPECT_EQ(cleaned->report.welded_vertices, 0);
  EXPECT_EQ(cleaned->report.dropped_duplicate_triangles, 0);
  EXPECT_EQ(cleaned->mesh.faces.size(), 2u);
}

// Nothing left, or coordinates that overflow in metres: INVALID_ARGUMENT.
TEST(CleaningTest, NothingLeftOrOverflowIsRefused) {
  RawMesh raw = SquareWithFaults();
  const std::vector<FaceInput> degenerate = {Triangle(0, 6, 1, 0, 0)};
  EXPECT_EQ(CleanMesh(raw, degenerate, {}).status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(CleanMesh(raw, {}, {}).status().code(), absl::StatusCode::kInvalidArgument);
  raw.positions[1] = Vector3d(1e300, 0, 0);
  ImportOptions huge;
  huge.unit_scale = 1e10;
  const std::vector<FaceInput> square = {Triangle(0, 1, 2, 0, 0)};
  const absl::Status overflow = CleanMesh(raw, square, huge).status();
  EXPECT_EQ(overflow.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(overflow.message().find("overflows"), std::string::npos) << overflow;
}

// Each way a reader's mesh can be malformed is named.
TEST(CleaningTest, MalformedRawMeshIsRefused) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<RawMesh> bad(5, SquareWithFaults());
  bad[0].positions[3] = Vector3d(0, nan, 0);
  const int32_t two[] = {0, 1};
  bad[1].AddPolygon(two, 0, 9);
  const int32_t out_of_range[] = {0, 1, 7};
  bad[2].AddPolygon(out_of_range, 0, 9);
  const int32_t fine[] = {0, 1, 2};
  bad[3].AddPolygon(fine, 2, 9);  // material 2 of 2
  bad[4].polygon_ids.pop_back();
  for (size_t i = 0; i < bad.size(); ++i) {
    EXPECT_EQ(ValidateRawMesh(bad[i]).code(), absl::StatusCode::kInvalidArgument) << i;
  }
  EXPECT_TRUE(ValidateRawMesh(SquareWithFaults()).ok());
}

// Options out of their documented ranges are named.
TEST(CleaningTest, OptionsOutOfRangeAreRefused) {
  const double inf = std::numeric_limits<double>::infinity();
  for (const double scale : {0.0, -1.0, inf, std::nan("")}) {
    ImportOptions options;
    options.unit_scale = scale;
    const absl::Status status = ValidateImportOptions(options);
    EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument) << scale;
    EXPECT_NE(status.message().find("unit_scale"), std::string::npos) << status;
  }
  for (const double weld : {-1e-9, inf, std::nan("")}) {
    ImportOptions options;
    options.weld_relative_tolerance = weld;
    const absl::Status status = ValidateImportOptions(options);
    EXPECT_NE(status.message().find("weld_relative_tolerance"), std::string::npos) << status;
  }
  ImportOptions options;
  options.default_material.stiffness_n_per_m = -1;
  EXPECT_NE(ValidateImportOptions(options).message().find("default_material"), std::string::npos);
  EXPECT_TRUE(ValidateImportOptions({}).ok());
}

}  // namespace
}  // namespace hs

#include "common/model/import.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <ostream>
#include <string>
#include <thread>
#include <vector>

#include "common/hds/mesh_report.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/common/scratch_dir.h"
#include "tests/common/test_data_dir.h"

namespace hs {
namespace {

using ::testing::ElementsAreArray;
using ::testing::HasSubstr;

Vector3d FaceNormal(const HapticObject& object, FaceId f) {
  const auto& v = object.face(f).vertices;
  const Vector3d& a = object.position(v[0]);
  return (object.position(v[1]) - a).cross(object.position(v[2]) - a);
}

double FaceArea(const HapticObject& object, FaceId f) { return 0.5 * FaceNormal(object, f).norm(); }

// Volume enclosed by the faces (divergence theorem): positive when every
// face is counter-clockwise seen from outside.
double SignedVolume(const HapticObject& object) {
  double six_volume = 0;
  for (FaceId f = 0; f < object.num_faces(); ++f) {
    const auto& v = object.face(f).vertices;
    six_volume += object.position(v[0]).dot(object.position(v[1]).cross(object.position(v[2])));
  }
  return six_volume / 6;
}

// Faces of each source polygon.
std::map<PolygonId, std::vector<FaceId>> FacesByPolygon(const HapticObject& object) {
  std::map<PolygonId, std::vector<FaceId>> groups;
  for (FaceId f = 0; f < object.num_faces(); ++f) {
    groups[object.face(f).source_polygon].push_back(f);
  }
  return groups;
}

std::vector<std::string> MaterialNames(const HapticObject& object) {
  std::vector<std::string> names;
  for (const Material& m : object.materials()) names.push_back(m.name);
  return names;
}

struct CubeFile {
  std::string file;
  std::string reader;
  /// Polygons of the file: 6 quads, or 12 triangles for STL.
  int polygons;
  std::vector<std::string> materials;
};

void PrintTo(const CubeFile& c, std::ostream* os) { *os << c.file; }

class ImportCubeTest : public ::testing::TestWithParam<CubeFile> {};

// The unit cube of every format imports as 8 vertices, 18 edges, 12 faces in [0,1]^3.
TEST_P(ImportCubeTest, CountsAndBox) {
  const CubeFile& c = GetParam();
  absl::StatusOr<ImportedModel> model = ImportModel(TestDataPath(c.file));
  ASSERT_TRUE(model.ok()) << model.status();
  const HapticObject& object = model->object;
  EXPECT_EQ(model->reader, c.reader);
  EXPECT_EQ(object.name(), std::filesystem::path(c.file).stem().string());
  EXPECT_EQ(object.num_vertices(), 8);
  EXPECT_EQ(object.num_edges(), 18);
  EXPECT_EQ(object.num_faces(), 12);
  // Every coordinate of the files is 0 or 1, exact in float and double.
  EXPECT_EQ(object.bounding_box().min(), Vector3d::Zero());
  EXPECT_EQ(object.bounding_box().max(), Vector3d::Ones());
}

// The imported cube is closed, consistently oriented, sphere-like and faces outward.
TEST_P(ImportCubeTest, ClosedAndOutward) {
  absl::StatusOr<ImportedModel> model = ImportModel(TestDataPath(GetParam().file));
  ASSERT_TRUE(model.ok()) << model.status();
  const MeshReport report = InspectMesh(model->object);
  EXPECT_TRUE(report.closed);
  EXPECT_TRUE(report.consistently_oriented);
  EXPECT_EQ(report.euler_characteristic, 2);
  EXPECT_EQ(report.connected_components, 1);
  EXPECT_TRUE(report.degenerate_faces.empty());
  EXPECT_EQ(report.duplicate_vertices, 0);
  EXPECT_EQ(report.unreferenced_vertices, 0);
  // Exact: every product in the sum is of 0s and 1s.
  EXPECT_EQ(SignedVolume(model->object), 1.0);
}

// Triangles cut from one file polygon share its id, and the ids count the file's polygons.
TEST_P(ImportCubeTest, Provenance) {
  const CubeFile& c = GetParam();
  absl::StatusOr<ImportedModel> model = ImportModel(TestDataPath(c.file));
  ASSERT_TRUE(model.ok()) << model.status();
  const HapticObject& object = model->object;
  const auto groups = FacesByPolygon(object);
  EXPECT_EQ(static_cast<int>(groups.size()), c.polygons);
  for (const auto& [polygon, faces] : groups) {
    EXPECT_NE(polygon, kNoPolygon);
    EXPECT_EQ(static_cast<int>(faces.size()), 12 / c.polygons) << "polygon " << polygon;
    // The triangles of one cube side share its outward normal.
    const Vector3d normal = FaceNormal(object, faces.front()).normalized();
    for (FaceId f : faces) {
      EXPECT_TRUE(FaceNormal(object, f).normalized().isApprox(normal)) << "face " << f;
    }
  }
  EXPECT_EQ(model->cleaning.input_polygons, c.polygons);
  EXPECT_EQ(model->cleaning.input_triangles, 12);
  EXPECT_EQ(model->cleaning.dropped_degenerate_triangles, 0);
  EXPECT_EQ(model->cleaning.dropped_duplicate_triangles, 0);
  EXPECT_EQ(model->cleaning.dropped_unreferenced_vertices, 0);
  EXPECT_EQ(model->cleaning.input_vertices - model->cleaning.welded_vertices, 8);
}

// Each material of the file becomes one HDS material with the default haptic parameters.
TEST_P(ImportCubeTest, Materials) {
  const CubeFile& c = GetParam();
  ImportOptions options;
  options.default_material.name = "fallback";
  options.default_material.stiffness_n_per_m = 2500;
  absl::StatusOr<ImportedModel> model = ImportModel(TestDataPath(c.file), options);
  ASSERT_TRUE(model.ok()) << model.status();
  const HapticObject& object = model->object;
  std::vector<std::string> expected = c.materials;
  if (expected.empty()) expected = {"fallback"};
  EXPECT_THAT(MaterialNames(object), ElementsAreArray(expected));
  for (const Material& m : object.materials()) {
    Material parameters = options.default_material;
    parameters.name = m.name;
    EXPECT_EQ(m, parameters);
  }
  // The two-material cubes give three sides to each material.
  std::vector<int> faces_per_material(object.materials().size(), 0);
  for (FaceId f = 0; f < object.num_faces(); ++f) ++faces_per_material[object.face(f).material];
  for (int count : faces_per_material) {
    EXPECT_EQ(count, object.num_faces() / static_cast<int>(object.materials().size()));
  }
}

// unit_scale converts file units to metres.
TEST_P(ImportCubeTest, UnitScale) {
  ImportOptions options;
  options.unit_scale = 0.001;
  absl::StatusOr<ImportedModel> model = ImportModel(TestDataPath(GetParam().file), options);
  ASSERT_TRUE(model.ok()) << model.status();
  EXPECT_EQ(model->object.bounding_box().min(), Vector3d::Zero());
  EXPECT_EQ(model->object.bounding_box().max(), Vector3d::Constant(0.001));
  EXPECT_EQ(model->object.num_vertices(), 8);
}

INSTANTIATE_TEST_SUITE_P(
    Formats, ImportCubeTest,
    ::testing::Values(CubeFile{"cube.obj", "assimp", 6, {"steel", "rubber"}},
                      CubeFile{"cube_ascii.stl", "assimp", 12, {}},
                      CubeFile{"cube_binary.stl", "assimp", 12, {}},
                      CubeFile{"cube.ply", "assimp", 6, {}}, CubeFile{"cube.off", "assimp", 6, {}},
                      CubeFile{"cube.dxf", "assimp", 6, {}},
                      CubeFile{"cube.iv", "coin3d", 6, {"steel", "rubber"}},
                      CubeFile{"cube.wrl", "coin3d", 6, {"steel", "rubber"}},
                      CubeFile{"cube_vrml1.wrl", "coin3d", 6, {"paint_0", "paint_1"}}),
    [](const ::testing::TestParamInfo<CubeFile>& info) {
      std::string name = info.param.file;
      for (char& ch : name) {
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
      }
      return name;
    });

// An STL repeats each corner per triangle; welding merges them to the cube's 8 and says so.
TEST(ImportWeldTest, StlCornersWelded) {
  absl::StatusOr<ImportedModel> model = ImportModel(TestDataPath("cube_binary.stl"));
  ASSERT_TRUE(model.ok()) << model.status();
  EXPECT_EQ(model->cleaning.input_vertices, 36);
  EXPECT_EQ(model->cleaning.welded_vertices, 28);
  EXPECT_EQ(model->object.num_vertices(), 8);
  EXPECT_TRUE(InspectMesh(model->object).closed);
}

// A weld tolerance of 0 still merges exactly coincident vertices.
TEST(ImportWeldTest, ZeroToleranceWeldsExactDuplicates) {
  ImportOptions options;
  options.weld_relative_tolerance = 0;
  absl::StatusOr<ImportedModel> model = ImportModel(TestDataPath("cube_ascii.stl"), options);
  ASSERT_TRUE(model.ok()) << model.status();
  EXPECT_EQ(model->cleaning.welded_vertices, 28);
  EXPECT_EQ(model->object.num_vertices(), 8);
}

// Vertices apart by less than the relative tolerance are welded; with tolerance 0 they are not.
TEST(ImportWeldTest, NearbyVerticesWeldedWithinTolerance) {
  // The cube's 12 triangles, each corner its own vertex, moved by up to 1e-9
  // (far below 1e-6 of the diagonal, far above rounding).
  const std::filesystem::path path = ScratchDir("weld") / "jittered.obj";
  {
    const double corners[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                  {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    const int triangles[12][3] = {{0, 3, 2}, {0, 2, 1}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                                  {2, 3, 7}, {2, 7, 6}, {0, 4, 7}, {0, 7, 3}, {1, 2, 6}, {1, 6, 5}};
    std::ofstream out(path);
    out.precision(17);
    int n = 0;
    for (const auto& t : triangles) {
      for (int c : t) {
        const double jitter = 1e-9 * ((n++ % 5) - 2) / 2.0;
        out << "v " << corners[c][0] + jitter << " " << corners[c][1] - jitter << " "
            << corners[c][2] + jitter << "\n";
      }
    }
    for (int f = 0; f < 12; ++f) {
      out << "f " << 3 * f + 1 << " " << 3 * f + 2 << " " << 3 * f + 3 << "\n";
    }
  }
  absl::StatusOr<ImportedModel> welded = ImportModel(path.string());
  ASSERT_TRUE(welded.ok()) << welded.status();
  EXPECT_EQ(welded->object.num_vertices(), 8);
  EXPECT_EQ(welded->cleaning.welded_vertices, 28);
  EXPECT_TRUE(InspectMesh(welded->object).closed);

  ImportOptions exact;
  exact.weld_relative_tolerance = 0;
  absl::StatusOr<ImportedModel> apart = ImportModel(path.string(), exact);
  ASSERT_TRUE(apart.ok()) << apart.status();
  EXPECT_GT(apart->object.num_vertices(), 8);
  EXPECT_FALSE(InspectMesh(apart->object, 0).closed);
}

// Degenerate, collapsed and duplicate triangles and the vertices they leave are dropped, counted.
TEST(ImportCleaningTest, DirtyCubeCleaned) {
  absl::StatusOr<ImportedModel> model = ImportModel(TestDataPath("dirty_cube.obj"));
  ASSERT_TRUE(model.ok()) << model.status();
  const CleaningReport& r = model->cleaning;
  EXPECT_EQ(r.input_polygons, 15);
  EXPECT_EQ(r.input_triangles, 15);
  // One collinear triangle, one that collapses when vertex 9 welds into 1.
  EXPECT_EQ(r.dropped_degenerate_triangles, 2);
  EXPECT_EQ(r.dropped_duplicate_triangles, 1);
  // The mid-edge vertex only the collinear triangle used.
  EXPECT_EQ(r.dropped_unreferenced_vertices, 1);
  EXPECT_EQ(r.input_vertices, r.welded_vertices + r.dropped_unreferenced_vertices + 8);
  EXPECT_EQ(model->object.num_vertices(), 8);
  EXPECT_EQ(model->object.num_faces(), 12);
  const MeshReport report = InspectMesh(model->object);
  EXPECT_TRUE(report.closed);
  EXPECT_TRUE(report.consistently_oriented);
  EXPECT_EQ(report.euler_characteristic, 2);
}

// A concave n-gon becomes n - 2 triangles that cover exactly its area.
TEST(ImportTriangulationTest, ConcavePolygon) {
  absl::StatusOr<ImportedModel> model = ImportModel(TestDataPath("l_prism.obj"));
  ASSERT_TRUE(model.ok()) << model.status();
  const HapticObject& object = model->object;
  EXPECT_EQ(model->cleaning.input_polygons, 8);
  EXPECT_EQ(object.num_vertices(), 12);
  EXPECT_EQ(object.num_faces(), 2 * 4 + 6 * 2);
  const auto groups = FacesByPolygon(object);
  ASSERT_EQ(groups.size(), 8u);
  // Polygons 0 and 1 are the L-shaped 6-gons (area 3); the rest are quads.
  for (const auto& [polygon, faces] : groups) {
    double area = 0;
    for (FaceId f : faces) area += FaceArea(object, f);
    if (polygon < 2) {
      EXPECT_EQ(faces.size(), 4u) << "polygon " << polygon;
      // Tolerance: rounding of a few products of small integers.
      EXPECT_NEAR(area, 3.0, 1e-12) << "polygon " << polygon;
    } else {
      EXPECT_EQ(faces.size(), 2u) << "polygon " << polygon;
    }
  }
  const MeshReport report = InspectMesh(object);
  EXPECT_TRUE(report.closed);
  EXPECT_TRUE(report.consistently_oriented);
  EXPECT_EQ(report.euler_characteristic, 2);
  EXPECT_NEAR(SignedVolume(object), 3.0, 1e-12);
}

// Node transforms are applied to every instance of a mesh and COLLADA's up axis does not turn it.
TEST(ImportTransformTest, AssimpNodeTransforms) {
  absl::StatusOr<ImportedModel> model = ImportModel(TestDataPath("two_cubes.dae"));
  ASSERT_TRUE(model.ok()) << model.status();
  const HapticObject& object = model->object;
  EXPECT_EQ(object.num_vertices(), 16);
  EXPECT_EQ(object.num_faces(), 24);
  EXPECT_EQ(FacesByPolygon(object).size(), 12u);
  EXPECT_EQ(object.bounding_box().min(), Vector3d::Zero());
  EXPECT_EQ(object.bounding_box().max(), Vector3d(4, 2, 2));
  const MeshReport report = InspectMesh(object);
  EXPECT_EQ(report.connected_components, 2);
  EXPECT_TRUE(report.closed);
  EXPECT_TRUE(report.consistently_oriented);
  EXPECT_EQ(SignedVolume(object), 1.0 + 8.0);
}

// A mirroring transform and a clockwise declaration in VRML still give outward-facing triangles.
TEST(ImportTransformTest, CoinMirrorAndClockwise) {
  absl::StatusOr<ImportedModel> model = ImportModel(TestDataPath("cube_mirrored.wrl"));
  ASSERT_TRUE(model.ok()) << model.status();
  const HapticObject& object = model->object;
  EXPECT_EQ(object.bounding_box().min(), Vector3d(2, 0, -1));
  EXPECT_EQ(object.bounding_box().max(), Vector3d(3, 1, 0));
  const MeshReport report = InspectMesh(object);
  EXPECT_TRUE(report.closed);
  EXPECT_TRUE(report.consistently_oriented);
  EXPECT_GT(SignedVolume(object), 0.999);
}

struct BadFile {
  std::string file;
  absl::StatusCode code;
  /// A piece of the reason the message must give.
  std::string reason;
};

void PrintTo(const BadFile& b, std::ostream* os) { *os << b.file; }

class ImportMalformedTest : public ::testing::TestWithParam<BadFile> {};

// A malformed file gives the documented error, naming the file and the reason, and never crashes.
TEST_P(ImportMalformedTest, ErrorNamesFile) {
  const BadFile& b = GetParam();
  absl::StatusOr<ImportedModel> model = ImportModel(TestDataPath(b.file));
  ASSERT_FALSE(model.ok());
  EXPECT_EQ(model.status().code(), b.code) << model.status();
  EXPECT_THAT(model.status().message(), HasSubstr(b.file));
  EXPECT_THAT(model.status().message(), HasSubstr(b.reason));
}

INSTANTIATE_TEST_SUITE_P(
    Malformed, ImportMalformedTest,
    ::testing::Values(
        BadFile{"truncated_binary.stl", absl::StatusCode::kInvalidArgument, "STL"},
        BadFile{"garbage.stl", absl::StatusCode::kInvalidArgument, "STL"},
        BadFile{"garbage.iv", absl::StatusCode::kInvalidArgument, "Not a valid Inventor file"},
        // assimp's OBJ reader accepts the bytes and returns an empty scene.
        BadFile{"garbage.obj", absl::StatusCode::kInvalidArgument, "no triangles"},
        BadFile{"truncated.iv", absl::StatusCode::kInvalidArgument, "got EOF"},
        BadFile{"nan.obj", absl::StatusCode::kInvalidArgument, "non-finite"},
        BadFile{"nan.iv", absl::StatusCode::kInvalidArgument, "Coin"},
        BadFile{"bad_index.obj", absl::StatusCode::kInvalidArgument, "index out of range"},
        BadFile{"bad_index.iv", absl::StatusCode::kInvalidArgument, "coordIndex[2] = 9"},
        BadFile{"empty.obj", absl::StatusCode::kInvalidArgument, "empty"},
        BadFile{"lines_only.obj", absl::StatusCode::kInvalidArgument, "no triangles"},
        BadFile{"missing.obj", absl::StatusCode::kNotFound, "no such file"}),
    [](const ::testing::TestParamInfo<BadFile>& info) {
      std::string name = info.param.file;
      for (char& ch : name) {
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
      }
      return name;
    });

// Options out of their documented range give INVALID_ARGUMENT naming the option.
TEST(ImportOptionsTest, BadOptionsRejected) {
  const std::string path = TestDataPath("cube.obj");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (double scale : {0.0, -1.0, nan, inf}) {
    ImportOptions options;
    options.unit_scale = scale;
    absl::StatusOr<ImportedModel> model = ImportModel(path, options);
    ASSERT_FALSE(model.ok()) << scale;
    EXPECT_EQ(model.status().code(), absl::StatusCode::kInvalidArgument);
    EXPECT_THAT(model.status().message(), HasSubstr("unit_scale"));
    EXPECT_THAT(model.status().message(), HasSubstr("cube.obj"));
  }
  for (double tolerance : {-1e-6, nan, inf}) {
    ImportOptions options;
    options.weld_relative_tolerance = tolerance;
    absl::StatusOr<ImportedModel> model = ImportModel(path, options);
    ASSERT_FALSE(model.ok()) << tolerance;
    EXPECT_EQ(model.status().code(), absl::StatusCode::kInvalidArgument);
    EXPECT_THAT(model.status().message(), HasSubstr("weld_relative_tolerance"));
  }
  ImportOptions options;
  options.default_material.stiffness_n_per_m = -1;
  absl::StatusOr<ImportedModel> model = ImportModel(path, options);
  ASSERT_FALSE(model.ok());
  EXPECT_EQ(model.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(model.status().message(), HasSubstr("default_material"));
}

// A directory is not a model file.
TEST(ImportFileTest, DirectoryRejected) {
  absl::StatusOr<ImportedModel> model = ImportModel(hs::TestDataDir());
  ASSERT_FALSE(model.ok());
  EXPECT_EQ(model.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(model.status().message(), HasSubstr("directory"));
}

// A file that cannot be opened for reading gives PERMISSION_DENIED.
TEST(ImportFileTest, UnreadableFileDenied) {
  const std::filesystem::path path = ScratchDir("denied") / "cube.obj";
  std::filesystem::copy_file(TestDataPath("cube.obj"), path);
  ASSERT_EQ(chmod(path.c_str(), 0), 0);
  if (access(path.c_str(), R_OK) == 0) GTEST_SKIP() << "running with rights to read any file";
  absl::StatusOr<ImportedModel> model = ImportModel(path.string());
  ASSERT_FALSE(model.ok());
  EXPECT_EQ(model.status().code(), absl::StatusCode::kPermissionDenied);
  EXPECT_THAT(model.status().message(), HasSubstr(path.string()));
}

// The reader is chosen by extension without regard to case.
TEST(ImportFileTest, ExtensionCaseIgnored) {
  const std::filesystem::path path = ScratchDir("case") / "CUBE.IV";
  std::filesystem::copy_file(TestDataPath("cube.iv"), path);
  absl::StatusOr<ImportedModel> model = ImportModel(path.string());
  ASSERT_TRUE(model.ok()) << model.status();
  EXPECT_EQ(model->reader, "coin3d");
  EXPECT_EQ(model->object.name(), "CUBE");
  EXPECT_EQ(model->object.num_faces(), 12);
}

// Imports from several threads at once all succeed (Coin is used under one lock).
TEST(ImportThreadTest, ConcurrentImports) {
  const std::vector<std::string> files = {"cube.iv",        "cube.wrl", "cube.obj",
                                          "l_prism.obj",    "cube.iv",  "truncated.iv",
                                          "cube_vrml1.wrl", "cube.ply"};
  std::vector<absl::Status> results(files.size());
  std::vector<std::thread> threads;
  for (size_t i = 0; i < files.size(); ++i) {
    threads.emplace_back([&, i] {
      for (int repeat = 0; repeat < 5 && results[i].ok(); ++repeat) {
        results[i] = ImportModel(TestDataPath(files[i])).status();
      }
    });
  }
  for (std::thread& t : threads) t.join();
  for (size_t i = 0; i < files.size(); ++i) {
    if (files[i] == "truncated.iv") {
      EXPECT_EQ(results[i].code(), absl::StatusCode::kInvalidArgument) << files[i];
    } else {
      EXPECT_TRUE(results[i].ok()) << files[i] << ": " << results[i];
    }
  }
}

}  // namespace
}  // namespace hs

#include "common/sandbox/import_codec.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <iterator>

#include "common/model/procedural.h"

namespace hs {
namespace {

namespace pb = haptics::internal;

// Options go into a job and come back field for field.
TEST(ImportCodecTest, OptionsRoundTrip) {
  const ImportOptions options{.unit_scale = 0.001,
                              .weld_relative_tolerance = 3e-5,
                              .default_material = {.name = "bone",
                                                   .stiffness_n_per_m = 5000,
                                                   .damping_ns_per_m = 2.5,
                                                   .static_friction = 0.6,
                                                   .dynamic_friction = 0.45}};
  pb::ImportJob job;
  OptionsToJob(options, job);
  const ImportOptions back = OptionsFromJob(job);
  EXPECT_EQ(back.unit_scale, options.unit_scale);
  EXPECT_EQ(back.weld_relative_tolerance, options.weld_relative_tolerance);
  EXPECT_EQ(back.default_material, options.default_material);
}

// A torus and a box of another material, with a report of every field.
ImportedModel TwoMaterialModel() {
  MeshInput torus = MakeTorus(0.1, 0.03, 12, 6);
  MeshInput box = MakeBox(Vector3d(0.02, 0.03, 0.04));
  box.materials[0] = {.name = "steel", .stiffness_n_per_m = 9000, .damping_ns_per_m = 3};
  return ImportedModel{*HapticObject::Create("part", MergeMeshes(torus, box)),
                       {.input_vertices = 300,
                        .input_polygons = 80,
                        .input_triangles = 156,
                        .welded_vertices = 12,
                        .dropped_unreferenced_vertices = 4,
                        .dropped_degenerate_triangles = 2,
                        .dropped_duplicate_triangles = 1},
                       "coin3d"};
}

// A model of two materials and their source polygons goes into a message
// and comes back the same object, report and reader.
TEST(ImportCodecTest, MeshRoundTrip) {
  const ImportedModel model = TwoMaterialModel();
  const absl::StatusOr<ImportedModel> back = MeshFromProto(MeshToProto(model));
  ASSERT_TRUE(back.ok()) << back.status();
  const HapticObject &a = model.object, &b = back->object;
  EXPECT_EQ(b.name(), "part");
  ASSERT_EQ(b.num_vertices(), a.num_vertices());
  for (VertexId v = 0; v < a.num_vertices(); ++v) EXPECT_EQ(b.position(v), a.position(v));
  ASSERT_EQ(b.num_faces(), a.num_faces());
  for (FaceId f = 0; f < a.num_faces(); ++f) {
    EXPECT_EQ(b.face(f).vertices, a.face(f).vertices);
    EXPECT_EQ(b.face(f).material, a.face(f).material);
    EXPECT_EQ(b.face(f).source_polygon, a.face(f).source_polygon);
  }
  ASSERT_EQ(b.materials().size(), 2u);
  EXPECT_EQ(b.materials()[0], a.materials()[0]);
  EXPECT_EQ(b.materials()[1], a.materials()[1]);
  EXPECT_EQ(back->reader, "coin3d");
  EXPECT_EQ(back->cleaning.input_vertices, 300);
  EXPECT_EQ(back->cleaning.input_polygons, 80);
  EXPECT_EQ(back->cleaning.input_triangles, 156);
  EXPECT_EQ(back->cleaning.welded_vertices, 12);
  EXPECT_EQ(back->cleaning.dropped_unreferenced_vertices, 4);
  EXPECT_EQ(back->cleaning.dropped_degenerate_triangles, 2);
  EXPECT_EQ(back->cleaning.dropped_duplicate_triangles, 1);
}

// A message whose arrays do not fit together, or whose mesh HapticObject
// refuses, is INVALID_ARGUMENT: the worker's output is not trusted.
TEST(ImportCodecTest, MalformedMeshesAreRefused) {
  const pb::ImportedMesh good = MeshToProto(TwoMaterialModel());
  const std::function<void(pb::ImportedMesh&)> spoilers[] = {
      [](pb::ImportedMesh& m) { m.add_positions(1); },      // not whole triples
      [](pb::ImportedMesh& m) { m.add_face_vertices(0); },  // not whole triangles
      [](pb::ImportedMesh& m) { m.mutable_face_polygons()->RemoveLast(); },
      [](pb::ImportedMesh& m) { m.set_face_vertices(5, 1 << 30); },   // vertex out of range
      [](pb::ImportedMesh& m) { m.set_face_materials(0, 7); },        // material out of range
      [](pb::ImportedMesh& m) { m.set_positions(4, std::nan("")); },  // not finite
      [](pb::ImportedMesh& m) { m.mutable_materials(1)->set_stiffness_n_per_m(-1); },
      [](pb::ImportedMesh& m) { m.clear_materials(); },
  };
  for (size_t i = 0; i < std::size(spoilers); ++i) {
    pb::ImportedMesh bad = good;
    spoilers[i](bad);
    EXPECT_EQ(MeshFromProto(bad).status().code(), absl::StatusCode::kInvalidArgument) << i;
  }
}

}  // namespace
}  // namespace hs

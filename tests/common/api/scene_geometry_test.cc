#include "common/api/scene_geometry.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "common/api/proto_convert.h"
#include "common/model/procedural.h"
#include "tests/common/sim/at_pose.h"

namespace hs {
namespace {

namespace pb = haptics::v1;

// A fixed box of two materials, a free box and a tool ball, each turned.
std::unique_ptr<Scene> ThreeObjects() {
  std::unique_ptr<Scene> scene = *Scene::Create({});
  MeshInput box = MakeBox(Vector3d(1, 1, 0.1));
  box.materials.push_back({.name = "soft", .stiffness_n_per_m = 80, .damping_ns_per_m = 0.5});
  box.faces[2].material = 1;
  Isometry3d X = At(0, 0, -0.05);
  X.rotate(Eigen::AngleAxisd(0.3, Vector3d::UnitZ()));
  EXPECT_TRUE(scene->AddObject(*HapticObject::Create("floor", box), ObjectKind::kFixed, X).ok());
  EXPECT_TRUE(scene
                  ->AddObject(*HapticObject::Create("cube", MakeBox(Vector3d::Constant(0.02))),
                              ObjectKind::kFree, At(0.2, 0, 0.3))
                  .ok());
  EXPECT_TRUE(scene
                  ->AddObject(*HapticObject::Create("ball", MakeIcosphere(0.01, 1)),
                              ObjectKind::kTool, At(0, 0.1, 0.2))
                  .ok());
  return scene;
}

// Each object comes out named, of its kind, at its pose, with its HDS
// vertices, faces, face materials, edges and materials in id order: a
// contact's feature ids index them.
TEST(SceneGeometryTest, ObjectsInIdOrder) {
  const std::unique_ptr<Scene> scene = ThreeObjects();
  const std::vector<std::string> names = {"floor", "cube", "ball"};
  pb::SceneGeometry geometry;
  SceneGeometryToProto(*scene, names, 5, &geometry);
  EXPECT_EQ(geometry.revision(), 5);
  ASSERT_EQ(geometry.objects_size(), 3);
  const pb::ObjectKind kinds[] = {pb::OBJECT_KIND_FIXED, pb::OBJECT_KIND_FREE,
                                  pb::OBJECT_KIND_TOOL};
  for (ObjectId id = 0; id < 3; ++id) {
    SCOPED_TRACE(id);
    const pb::ObjectGeometry& g = geometry.objects(id);
    const SceneObjects::Object& o = scene->object(id);
    const HapticObject& mesh = o.object;
    EXPECT_EQ(g.name(), names[id]);
    EXPECT_EQ(g.kind(), kinds[id]);
    const absl::StatusOr<Isometry3d> pose = PoseFromProto(g.pose(), "pose");
    ASSERT_TRUE(pose.ok());
    EXPECT_TRUE(pose->isApprox(o.X_WO, 1e-12));
    ASSERT_EQ(g.vertices_m_size(), 3 * mesh.num_vertices());
    for (VertexId v = 0; v < mesh.num_vertices(); ++v) {
      for (int k = 0; k < 3; ++k) EXPECT_EQ(g.vertices_m(3 * v + k), mesh.position(v)[k]);
    }
    ASSERT_EQ(g.triangles_size(), 3 * mesh.num_faces());
    ASSERT_EQ(g.face_materials_size(), mesh.num_faces());
    for (FaceId f = 0; f < mesh.num_faces(); ++f) {
      for (int k = 0; k < 3; ++k) EXPECT_EQ(g.triangles(3 * f + k), mesh.face(f).vertices[k]);
      EXPECT_EQ(g.face_materials(f), mesh.face(f).material);
    }
    ASSERT_EQ(g.edges_size(), 2 * mesh.num_edges());
    for (EdgeId e = 0; e < mesh.num_edges(); ++e) {
      EXPECT_EQ(g.edges(2 * e), mesh.edge(e).vertices[0]);
      EXPECT_EQ(g.edges(2 * e + 1), mesh.edge(e).vertices[1]);
    }
    ASSERT_EQ(g.materials_size(), static_cast<int>(mesh.materials().size()));
    for (size_t m = 0; m < mesh.materials().size(); ++m) {
      EXPECT_EQ(g.materials(m).stiffness_n_per_m(), mesh.materials()[m].stiffness_n_per_m);
      EXPECT_EQ(g.materials(m).damping_ns_per_m(), mesh.materials()[m].damping_ns_per_m);
      EXPECT_EQ(g.materials(m).static_friction(), mesh.materials()[m].static_friction);
      EXPECT_EQ(g.materials(m).dynamic_friction(), mesh.materials()[m].dynamic_friction);
    }
  }
  EXPECT_EQ(geometry.objects(0).materials(1).stiffness_n_per_m(), 80);
  EXPECT_EQ(geometry.objects(0).face_materials(2), 1);
}

// The message is written over: what it held before is gone.
TEST(SceneGeometryTest, WritesOver) {
  const std::unique_ptr<Scene> scene = ThreeObjects();
  pb::SceneGeometry geometry;
  geometry.set_scene("old");
  geometry.add_objects()->set_name("stale");
  SceneGeometryToProto(*scene, {"floor", "cube", "ball"}, 1, &geometry);
  EXPECT_EQ(geometry.scene(), "");
  ASSERT_EQ(geometry.objects_size(), 3);
  EXPECT_EQ(geometry.objects(0).name(), "floor");
}

}  // namespace
}  // namespace hs

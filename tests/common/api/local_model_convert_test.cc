#include "common/api/local_model_convert.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <limits>
#include <memory>
#include <random>
#include <string>

#include "tests/common/random_poses.h"

namespace hs {
namespace {

namespace pb = haptics::v1;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A model with `planes` random planes of objects 0..2, every field set.
LocalModel RandomModel(std::mt19937& rng, int planes) {
  std::uniform_real_distribution<double> u(0.01, 1);
  LocalModel model;
  model.X_WP = testing_poses::RandomPose(rng, 1);
  model.p_WD = Vector3d(u(rng), u(rng), u(rng));
  model.validity_radius_m = u(rng);
  model.force_clamp_n = 10 * u(rng);
  model.touching = rng() % 2;
  model.touch_point_W = Vector3d(u(rng), -u(rng), u(rng));
  model.friction = rng() % 2;
  for (int i = 0; i < planes; ++i) {
    ConstraintPlane& p = model.planes.emplace_back();
    p.object = static_cast<int32_t>(rng() % 3);
    p.point_W = Vector3d(u(rng), u(rng), -u(rng));
    p.normal_W = testing_poses::RandomDirection(rng);
    p.gap_m = u(rng) / 100;
    p.tool_point_W = p.point_W + p.gap_m * p.normal_W;
    p.stiffness_n_per_m = 1000 * u(rng);
    p.damping_ns_per_m = u(rng);
    p.static_friction = u(rng);
    p.dynamic_friction = p.static_friction * u(rng);
    p.separating = rng() % 2;
  }
  return model;
}

// A surface of `faces` random triangles (sharing vertices), a tetrahedron
// as the tool, and two random materials.
std::shared_ptr<const ModelSurface> RandomSurface(std::mt19937& rng, int faces) {
  std::uniform_real_distribution<double> u(-1, 1);
  auto s = std::make_shared<ModelSurface>();
  s->revision = 1 + rng() % 100;
  s->center_W = Vector3d(u(rng), u(rng), u(rng));
  s->radius_m = 0.5 + u(rng) / 4;
  s->tool_vertices_T = {Vector3d::Zero(), Vector3d::UnitX(), Vector3d::UnitY(), Vector3d::UnitZ()};
  s->tool_triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  for (int i = 0; i < faces + 2; ++i) s->vertices_W.emplace_back(u(rng), u(rng), u(rng));
  for (int i = 0; i < faces; ++i) {
    s->triangles.push_back({i, i + 1, i + 2});
    s->triangle_materials.push_back(static_cast<int32_t>(rng() % 2));
  }
  for (int i = 0; i < 2; ++i) {
    const double mu = (u(rng) + 1) / 2;
    s->materials.push_back({1000 * mu + 1, mu, mu, mu / 2});
  }
  return s;
}

const std::vector<std::string> kNames = {"table", "organ", "probe"};

// The number a model read back gives `object`: how many other objects the
// model names before it first names `object`.
int32_t FirstNamed(const LocalModel& model, int32_t object) {
  std::vector<int32_t> seen;
  for (const ConstraintPlane& p : model.planes) {
    if (p.object == object) break;
    if (std::find(seen.begin(), seen.end(), p.object) == seen.end()) seen.push_back(p.object);
  }
  return static_cast<int32_t>(seen.size());
}

// To the proto and back gives the model again, field for field, but the
// planes' objects, which go out by name and come back numbered in the
// order the model first names them: two planes share a number exactly
// when they share an object.
TEST(LocalModelConvertTest, RoundTrip) {
  std::mt19937 rng(6);
  for (int k = 0; k < 50; ++k) {
    const LocalModel model = RandomModel(rng, k % 5);
    pb::LocalModel proto;
    LocalModelToProto(model, kNames, &proto);
    const absl::StatusOr<LocalModel> back = LocalModelFromProto(proto);
    ASSERT_TRUE(back.ok()) << back.status();
    EXPECT_TRUE(back->X_WP.isApprox(model.X_WP, 1e-12));
    EXPECT_EQ(back->p_WD, model.p_WD);
    EXPECT_EQ(back->validity_radius_m, model.validity_radius_m);
    EXPECT_EQ(back->force_clamp_n, model.force_clamp_n);
    EXPECT_EQ(back->touching, model.touching);
    EXPECT_EQ(back->touch_point_W, model.touch_point_W);
    EXPECT_EQ(back->friction, model.friction);
    ASSERT_EQ(back->planes.size(), model.planes.size());
    for (size_t i = 0; i < model.planes.size(); ++i) {
      const ConstraintPlane &got = back->planes[i], &want = model.planes[i];
      EXPECT_EQ(proto.planes(i).object(), kNames[want.object]);
      EXPECT_EQ(got.object, FirstNamed(model, want.object));
      EXPECT_EQ(got.separating, want.separating);
      EXPECT_EQ(got.point_W, want.point_W);
      EXPECT_EQ(got.normal_W, want.normal_W);
      EXPECT_EQ(got.gap_m, want.gap_m);
      EXPECT_EQ(got.tool_point_W, want.tool_point_W);
      EXPECT_EQ(got.stiffness_n_per_m, want.stiffness_n_per_m);
      EXPECT_EQ(got.damping_ns_per_m, want.damping_ns_per_m);
      EXPECT_EQ(got.static_friction, want.static_friction);
      EXPECT_EQ(got.dynamic_friction, want.dynamic_friction);
    }
  }
}

// A surface goes out and comes back field for field with its faces, and
// as its revision, centre and radius alone without them (for a stream
// that has them).
TEST(LocalModelConvertTest, SurfaceRoundTripsWithAndWithoutItsFaces) {
  std::mt19937 rng(8);
  for (int k = 0; k < 20; ++k) {
    LocalModel model = RandomModel(rng, 1);
    model.surface = RandomSurface(rng, k);
    for (const bool faces : {true, false}) {
      pb::LocalModel proto;
      LocalModelToProto(model, kNames, &proto, faces);
      const absl::StatusOr<LocalModel> back = LocalModelFromProto(proto);
      ASSERT_TRUE(back.ok()) << back.status();
      ASSERT_TRUE(back->surface);
      const ModelSurface &got = *back->surface, &want = *model.surface;
      EXPECT_EQ(got.revision, want.revision);
      EXPECT_EQ(got.center_W, want.center_W);
      EXPECT_EQ(got.radius_m, want.radius_m);
      EXPECT_EQ(got.has_body(), faces);
      if (!faces) continue;
      EXPECT_EQ(got.tool_vertices_T, want.tool_vertices_T);
      EXPECT_EQ(got.tool_triangles, want.tool_triangles);
      EXPECT_EQ(got.vertices_W, want.vertices_W);
      EXPECT_EQ(got.triangles, want.triangles);
      EXPECT_EQ(got.triangle_materials, want.triangle_materials);
      ASSERT_EQ(got.materials.size(), want.materials.size());
      for (size_t i = 0; i < got.materials.size(); ++i) {
        EXPECT_EQ(got.materials[i].stiffness_n_per_m, want.materials[i].stiffness_n_per_m);
        EXPECT_EQ(got.materials[i].dynamic_friction, want.materials[i].dynamic_friction);
      }
    }
  }
  pb::LocalModel none;
  LocalModelToProto(RandomModel(rng, 1), kNames, &none);
  EXPECT_FALSE(none.has_surface());
  EXPECT_EQ(LocalModelFromProto(none)->surface, nullptr);
}

// Each field out of its range, its surface's too (a bad index, a count
// past its cap, a triple cut short), makes the whole model
// INVALID_ARGUMENT, naming that field.
TEST(LocalModelConvertTest, BadFieldsAreNamed) {
  std::mt19937 rng(7);
  LocalModel model = RandomModel(rng, 2);
  model.surface = RandomSurface(rng, 3);
  pb::LocalModel good;
  LocalModelToProto(model, kNames, &good);
  ASSERT_TRUE(LocalModelFromProto(good).ok());
  struct Case {
    const char* field;
    std::function<void(pb::LocalModel&)> spoil;
  };
  const Case cases[] = {
      {"validity_radius_m", [](pb::LocalModel& m) { m.set_validity_radius_m(0); }},
      {"validity_radius_m", [](pb::LocalModel& m) { m.set_validity_radius_m(kNaN); }},
      {"force_clamp_n", [](pb::LocalModel& m) { m.set_force_clamp_n(-1); }},
      {"touch_point_W_m", [](pb::LocalModel& m) { m.mutable_touch_point_w_m()->set_x(kNaN); }},
      {"device_position_W_m",
       [](pb::LocalModel& m) { m.mutable_device_position_w_m()->set_z(1e300); }},
      {"planes[1].normal_W",
       [](pb::LocalModel& m) { m.mutable_planes(1)->mutable_normal_w()->set_x(2); }},
      {"planes[0].gap_m", [](pb::LocalModel& m) { m.mutable_planes(0)->set_gap_m(-1e-9); }},
      {"planes[0].point_W_m",
       [](pb::LocalModel& m) { m.mutable_planes(0)->mutable_point_w_m()->set_y(kNaN); }},
      {"planes[1].material.stiffness_n_per_m",
       [](pb::LocalModel& m) {
         m.mutable_planes(1)->mutable_material()->set_stiffness_n_per_m(0);
       }},
      {"planes[1].material.damping_ns_per_m",
       [](pb::LocalModel& m) {
         m.mutable_planes(1)->mutable_material()->set_damping_ns_per_m(-1);
       }},
      {"planes[0].material.dynamic_friction",
       [](pb::LocalModel& m) {
         pb::Material* material = m.mutable_planes(0)->mutable_material();
         material->set_dynamic_friction(material->static_friction() * 1.5 + 0.1);
       }},
      {"surface.radius_m",
       [](pb::LocalModel& m) {
         pb::ModelSurface& s = *m.mutable_surface();
         s.set_radius_m(0);
       }},
      {"surface.center_W_m",
       [](pb::LocalModel& m) {
         pb::ModelSurface& s = *m.mutable_surface();
         s.mutable_center_w_m()->set_x(kNaN);
       }},
      {"surface.vertices_W_m",
       [](pb::LocalModel& m) {
         pb::ModelSurface& s = *m.mutable_surface();
         s.add_vertices_w_m(0);
       }},
      {"surface.vertices_W_m",
       [](pb::LocalModel& m) {
         pb::ModelSurface& s = *m.mutable_surface();
         s.set_vertices_w_m(4, kNaN);
       }},
      {"surface.triangles",
       [](pb::LocalModel& m) {
         pb::ModelSurface& s = *m.mutable_surface();
         s.set_triangles(2, 1000);
       }},
      {"surface.triangles",
       [](pb::LocalModel& m) {
         pb::ModelSurface& s = *m.mutable_surface();
         s.set_triangles(1, s.triangles(0));
       }},
      {"surface.triangles",
       [](pb::LocalModel& m) {
         pb::ModelSurface& s = *m.mutable_surface();
         s.add_triangles(0);
       }},
      {"surface.face_materials",
       [](pb::LocalModel& m) {
         pb::ModelSurface& s = *m.mutable_surface();
         s.set_face_materials(0, 2);
       }},
      {"surface.face_materials",
       [](pb::LocalModel& m) {
         pb::ModelSurface& s = *m.mutable_surface();
         s.add_face_materials(0);
       }},
      {"surface.tool_triangles",
       [](pb::LocalModel& m) {
         pb::ModelSurface& s = *m.mutable_surface();
         s.set_tool_triangles(0, 4);
       }},
      {"surface.tool_triangles",
       [](pb::LocalModel& m) {
         pb::ModelSurface& s = *m.mutable_surface();
         s.clear_tool_triangles();
       }},
      {"surface.tool_vertices_T_m",
       [](pb::LocalModel& m) {
         pb::ModelSurface& s = *m.mutable_surface();
         for (int i = 0; i < 3 * kMaxToolHullVertices; ++i) s.add_tool_vertices_t_m(0);
       }},
      {"surface.materials[1].stiffness_n_per_m",
       [](pb::LocalModel& m) {
         pb::ModelSurface& s = *m.mutable_surface();
         s.mutable_materials(1)->set_stiffness_n_per_m(-1);
       }},
  };
  for (const Case& c : cases) {
    pb::LocalModel bad = good;
    c.spoil(bad);
    const absl::StatusOr<LocalModel> model = LocalModelFromProto(bad);
    EXPECT_EQ(model.status().code(), absl::StatusCode::kInvalidArgument) << c.field;
    EXPECT_NE(model.status().message().find(c.field), std::string::npos) << model.status();
  }
}

}  // namespace
}  // namespace hs

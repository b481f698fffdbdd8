// Which planes of a local model separate the tool from their object: on a
// box table its top's, on a torus's outer crest the plane through its
// highest corner under the tool, on its inner wall (a saddle) none; each
// marking checked against every corner of the object near the tool and of
// the tool (brute force).

#include "common/sim/separating_planes.h"

#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <vector>

#include "common/model/procedural.h"
#include "common/sim/local_model_builder.h"
#include "tests/common/contact/contact_test_bodies.h"
#include "tests/common/sim/at_pose.h"

namespace hs {
namespace {

using testing_bodies::Body;
using testing_bodies::MakeBody;

constexpr double kRadius = 0.01;
// Rounding, as the marking allows it (relative to the larger box).
constexpr double kSlack = 1e-9;

struct Scene {
  std::unique_ptr<Body> tool;
  std::unique_ptr<Body> object;
};

// A 2 cm cube tool and `object`; the model of the tool at `X_WP`, marked.
LocalModel MarkedModel(const Scene& scene, const Isometry3d& X_WP) {
  ProxyState proxy;
  proxy.X_WP = X_WP;
  const PosedObject object = scene.object->posed();
  const ObjectId id = 0;
  LocalModel model;
  const PosedObject tool{&scene.tool->object, &scene.tool->model, X_WP};
  BuildLocalModel(tool, proxy, X_WP.translation(), {&object, 1}, {&id, 1}, {.radius_m = kRadius},
                  model);
  SeparationMemo memo;
  MarkSeparatingPlanes(tool, {&object, 1}, {&id, 1}, memo, model);
  return model;
}

// The farthest a corner of the object's faces within `reach_m` of the
// tool's box lies in front of `plane`, and the farthest a tool corner lies
// behind it through its tool point: every corner, brute force.
struct Worst {
  double object_in_front = -1;
  double tool_behind = -1;
};
Worst WorstCorners(const Scene& scene, const Isometry3d& X_WP, const ConstraintPlane& plane,
                   double reach_m) {
  AlignedBox3d tool_box;
  const HapticObject& t = scene.tool->object;
  for (VertexId v = 0; v < t.num_vertices(); ++v) tool_box.extend(X_WP * t.position(v));
  const AlignedBox3d near(tool_box.min().array() - reach_m, tool_box.max().array() + reach_m);
  Worst worst;
  const HapticObject& o = scene.object->object;
  for (FaceId f = 0; f < o.num_faces(); ++f) {
    AlignedBox3d face_box;
    for (const VertexId v : o.face(f).vertices) face_box.extend(scene.object->X_WO * o.position(v));
    if (!face_box.intersects(near)) continue;
    for (const VertexId v : o.face(f).vertices) {
      const Vector3d x = scene.object->X_WO * o.position(v);
      worst.object_in_front =
          std::max(worst.object_in_front, plane.normal_W.dot(x - plane.point_W));
    }
  }
  for (VertexId v = 0; v < t.num_vertices(); ++v) {
    worst.tool_behind =
        std::max(worst.tool_behind, -plane.normal_W.dot(X_WP * t.position(v) - plane.tool_point_W));
  }
  return worst;
}

// Counts the model's separating planes, checking each marking: a plane
// marked separating has no object corner near the tool (within the radius
// of its box) in front of it and no tool corner behind it; one not marked
// has such a corner somewhere near (the region checked reaches out to a
// grid of the radius, and the hierarchy's volumes twice a face's size
// beyond it: within four radii).
int CheckedSeparating(const Scene& scene, const Isometry3d& X_WP, const LocalModel& model) {
  const double slack = kSlack * scene.object->object.bounding_box().diagonal().norm() * 2;
  int separating = 0;
  for (const ConstraintPlane& plane : model.planes) {
    if (plane.separating) {
      const Worst worst = WorstCorners(scene, X_WP, plane, kRadius);
      EXPECT_LE(worst.object_in_front, slack);
      EXPECT_LE(worst.tool_behind, slack);
      ++separating;
    } else {
      const Worst worst = WorstCorners(scene, X_WP, plane, 4 * kRadius);
      EXPECT_TRUE(worst.object_in_front > 0 || worst.tool_behind > 0);
    }
  }
  return separating;
}

Scene MakeScene(MeshInput object, const Isometry3d& X_WO) {
  return {MakeBody(MakeBox(Vector3d::Constant(0.02))), MakeBody(std::move(object), X_WO)};
}

// A cube over a box table, at random heights, shifts and turns about the
// vertical: the plane of the table's top separates them. (A plane through
// the top's diagonal, an edge pair across the flat edge between its two
// triangles, does not: the top's far corners lie in front of it.)
TEST(SeparatingPlanesTest, ThePlaneOfATablesTopSeparates) {
  const Scene scene = MakeScene(MakeBox(Vector3d(1, 1, 0.05)), At(0, 0, -0.025));
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 30; ++trial) {
    Isometry3d X_WP = At(0.1 * u(rng), 0.1 * u(rng), 0.0101 + 0.004 * (u(rng) + 1));
    X_WP.linear() = Eigen::AngleAxisd(u(rng), Vector3d::UnitZ()).toRotationMatrix();
    const LocalModel model = MarkedModel(scene, X_WP);
    (void)CheckedSeparating(scene, X_WP, model);
    int tops = 0;
    for (const ConstraintPlane& plane : model.planes) {
      if (plane.normal_W != Vector3d::UnitZ()) continue;
      ++tops;
      EXPECT_TRUE(plane.separating) << trial;
    }
    EXPECT_EQ(tops, 1) << trial;
  }
}

// The demo's organ (a torus of radii 0.1 and 0.04 m about z): over the
// top of its tube, which holds the whole torus under it, a plane through
// the highest corner under the cube's flat bottom separates (the planes of
// lower corners, and those of edge pairs tilted along the ring, do not);
// against its inner wall (around the hole, a saddle: the wall curves in
// front of its own tangent planes) none does.
TEST(SeparatingPlanesTest, TheTopOfATorusSeparatesAndASaddleDoesNot) {
  const Scene scene = MakeScene(MakeTorus(0.1, 0.04, 96, 48), At(0, 0, 0.04));
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  int saddle_planes = 0;
  for (int trial = 0; trial < 20; ++trial) {
    // Resting on the top of the tube, 1-5 mm up, anywhere along it.
    const double around = 3.14 * u(rng);
    const Vector3d top(0.1 * std::cos(around), 0.1 * std::sin(around), 0.08);
    Isometry3d X_WP = At(0, 0, 0);
    X_WP.linear() = Eigen::AngleAxisd(around, Vector3d::UnitZ()).toRotationMatrix();
    X_WP.translation() = top + Vector3d(0, 0, 0.011 + 0.002 * (u(rng) + 1));
    const LocalModel on_crest = MarkedModel(scene, X_WP);
    EXPECT_GE(CheckedSeparating(scene, X_WP, on_crest), 1) << trial;
    // In the hole, 1-5 mm from the inner wall, at the tube's height.
    const Vector3d wall(0.06 * std::cos(around), 0.06 * std::sin(around), 0.04);
    X_WP.translation() = wall * (1 - (0.011 + 0.002 * (u(rng) + 1)) / 0.06);
    const LocalModel in_hole = MarkedModel(scene, X_WP);
    EXPECT_EQ(CheckedSeparating(scene, X_WP, in_hole), 0) << trial;
    saddle_planes += static_cast<int>(in_hole.planes.size());
  }
  EXPECT_GT(saddle_planes, 20);
}

}  // namespace
}  // namespace hs

#include "common/sim/local_model_builder.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <optional>
#include <random>
#include <vector>

#include "common/collision/triangle_pairs.h"
#include "common/model/procedural.h"
#include "tests/common/contact/contact_test_bodies.h"
#include "tests/common/random_poses.h"
#include "tests/common/sanitized_build.h"
#include "tests/common/sim/at_pose.h"

namespace hs {
namespace {

using testing_bodies::Body;
using testing_bodies::MakeBody;

constexpr double kTool = 0.02;  // the tool: a cube of this side
constexpr double kRadius = 0.01;

// A 1 m x 1 m x 0.1 m floor with its top at z = 0, its material `material`.
std::unique_ptr<Body> Floor(const Material& material = {}) {
  MeshInput mesh = MakeBox(Vector3d(1, 1, 0.1));
  mesh.materials[0] = material;
  return MakeBody(std::move(mesh), At(0, 0, -0.05));
}

std::unique_ptr<Body> Tool() { return MakeBody(MakeBox(Vector3d::Constant(kTool))); }

ProxyState ProxyAt(const Isometry3d& X_WP) {
  ProxyState proxy;
  proxy.X_WP = X_WP;
  return proxy;
}

LocalModel Build(const Body& tool, const ProxyState& proxy,
                 const std::vector<const Body*>& obstacles, const std::vector<ObjectId>& ids,
                 const LocalModelOptions& options = {.radius_m = kRadius}) {
  std::vector<PosedObject> posed;
  for (const Body* body : obstacles) posed.push_back(body->posed());
  LocalModel model;
  BuildLocalModel(tool.posed(), proxy, proxy.X_WP.translation() + Vector3d(0, 0, -0.001), posed,
                  ids, options, model);
  return model;
}

// A point at the lever moves at most by the shift plus the turn's arc:
// the bound holds for every point of a tool within the lever, checked on
// random poses against the points of a sphere of that radius (brute force).
TEST(LocalModelBuilderTest, MovedByBoundsEveryPointWithinTheLever) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  constexpr double kLever = 0.05;
  for (int trial = 0; trial < 200; ++trial) {
    Isometry3d from = Isometry3d::Identity(), to = Isometry3d::Identity();
    from.linear() = Eigen::Quaterniond::UnitRandom().toRotationMatrix();
    to.linear() = (Eigen::AngleAxisd(0.3 * u(rng), Vector3d(u(rng), u(rng), u(rng)).normalized()) *
                   from.linear());
    from.translation() = 0.01 * Vector3d(u(rng), u(rng), u(rng));
    to.translation() = 0.01 * Vector3d(u(rng), u(rng), u(rng));
    const double bound = MovedBy(from, to, kLever);
    double worst = 0;
    for (int k = 0; k < 200; ++k) {
      const Vector3d p_O = kLever * Vector3d(u(rng), u(rng), u(rng)).normalized();
      worst = std::max(worst, (to * p_O - from * p_O).norm());
    }
    EXPECT_LE(worst, bound + 1e-15) << trial;
    EXPECT_GE(bound, (to.translation() - from.translation()).norm());
  }
  EXPECT_EQ(MovedBy(Isometry3d::Identity(), Isometry3d::Identity(), kLever), 0);
}

// A tool `gap` above the floor: one plane (its four bottom corners over the
// floor's top give the same plane), the floor's top, with the floor's id
// and material; the model carries the proxy, the device and the options.
TEST(LocalModelBuilderTest, FloorUnderTheToolGivesItsPlane) {
  const Material material{.name = "felt",
                          .stiffness_n_per_m = 700,
                          .damping_ns_per_m = 2,
                          .static_friction = 0.5,
                          .dynamic_friction = 0.4};
  const auto floor = Floor(material);
  auto tool = Tool();
  tool->X_WO = At(5, 5, 5);  // ignored: the proxy places the tool
  const double gap = 0.004;
  const ProxyState proxy = ProxyAt(At(0.1, 0.05, kTool / 2 + gap));
  const LocalModelOptions options{
      .radius_m = kRadius, .max_planes = 4, .force_clamp_n = 7, .friction = true};
  const LocalModel model = Build(*tool, proxy, {floor.get()}, {42}, options);
  EXPECT_TRUE(model.X_WP.isApprox(proxy.X_WP));
  EXPECT_EQ(model.p_WD, Vector3d(0.1, 0.05, kTool / 2 + gap - 0.001));
  EXPECT_EQ(model.validity_radius_m, kRadius);
  EXPECT_EQ(model.force_clamp_n, 7);
  EXPECT_TRUE(model.friction);
  ASSERT_EQ(model.planes.size(), 1u);
  const ConstraintPlane& plane = model.planes[0];
  EXPECT_EQ(plane.object, 42);
  EXPECT_TRUE(plane.normal_W.isApprox(Vector3d::UnitZ(), 1e-12));
  EXPECT_NEAR(plane.gap_m, gap, 1e-12);
  EXPECT_NEAR(plane.point_W.z(), 0, 1e-12);
  // The tool's point is a bottom corner, straight above the plane's point.
  EXPECT_NEAR(std::abs(plane.tool_point_W.x() - 0.1), kTool / 2, 1e-12);
  EXPECT_NEAR(std::abs(plane.tool_point_W.y() - 0.05), kTool / 2, 1e-12);
  EXPECT_TRUE((plane.tool_point_W - plane.point_W).isApprox(gap * Vector3d::UnitZ(), 1e-9));
  EXPECT_EQ(plane.stiffness_n_per_m, 700);
  EXPECT_EQ(plane.damping_ns_per_m, 2);
  EXPECT_EQ(plane.static_friction, 0.5);
  EXPECT_EQ(plane.dynamic_friction, 0.4);
}

// The floor counts while the tool is within the radius of it, not beyond.
TEST(LocalModelBuilderTest, OnlyFacesWithinTheRadiusGivePlanes) {
  const auto floor = Floor();
  const auto tool = Tool();
  EXPECT_EQ(
      Build(*tool, ProxyAt(At(0, 0, kTool / 2 + 0.99 * kRadius)), {floor.get()}, {0}).planes.size(),
      1u);
  EXPECT_TRUE(Build(*tool, ProxyAt(At(0, 0, kTool / 2 + 1.01 * kRadius)), {floor.get()}, {0})
                  .planes.empty());
}

// A touching proxy's model holds its contact point as the lever; a free
// one's the proxy's origin.
TEST(LocalModelBuilderTest, TouchPointIsTheContactOrTheProxyOrigin) {
  const auto floor = Floor();
  const auto tool = Tool();
  ProxyState proxy = ProxyAt(At(0.1, 0.05, kTool / 2));
  LocalModel model = Build(*tool, proxy, {floor.get()}, {0});
  EXPECT_FALSE(model.touching);
  EXPECT_EQ(model.touch_point_W, proxy.X_WP.translation());
  proxy.touching = true;
  proxy.p_WC = Vector3d(0.1, 0.05, 0);
  model = Build(*tool, proxy, {floor.get()}, {0});
  EXPECT_TRUE(model.touching);
  EXPECT_EQ(model.touch_point_W, proxy.p_WC);
}

// SetModelState writes the proxy and every option over what a model held,
// and leaves its planes, surface and revision as they were.
TEST(LocalModelBuilderTest, ModelStateIsTheProxyAndTheOptions) {
  ProxyState proxy = ProxyAt(At(0.1, 0.05, 0.2));
  proxy.touching = true;
  proxy.p_WC = Vector3d(0.1, 0.05, 0.19);
  const LocalModelOptions options{
      .radius_m = 0.03, .max_planes = 4, .force_clamp_n = 7, .friction = true};
  LocalModel model;
  model.planes.resize(2);
  model.revision = 5;
  SetModelState(proxy, Vector3d(0.1, 0.05, 0.18), options, model);
  EXPECT_TRUE(model.X_WP.isApprox(proxy.X_WP, 0.0));
  EXPECT_EQ(model.p_WD, Vector3d(0.1, 0.05, 0.18));
  EXPECT_TRUE(model.touching);
  EXPECT_EQ(model.touch_point_W, proxy.p_WC);
  EXPECT_EQ(model.validity_radius_m, 0.03);
  EXPECT_EQ(model.force_clamp_n, 7);
  EXPECT_TRUE(model.friction);
  EXPECT_EQ(model.planes.size(), 2u);
  EXPECT_EQ(model.revision, 5u);
}

// In an inside corner (a floor and a wall at x = 0.2) the tool gets both
// planes, nearest first; a cap of one keeps the nearer.
TEST(LocalModelBuilderTest, PlanesAreNearestFirstAndCapped) {
  const auto floor = Floor();
  const auto wall = MakeBody(MakeBox(Vector3d(0.1, 1, 1)), At(0.25, 0, 0.5));
  const auto tool = Tool();
  const ProxyState proxy = ProxyAt(At(0.2 - kTool / 2 - 0.002, 0, kTool / 2 + 0.005));
  const LocalModel model = Build(*tool, proxy, {floor.get(), wall.get()}, {1, 2});
  ASSERT_EQ(model.planes.size(), 2u);
  EXPECT_EQ(model.planes[0].object, 2);
  EXPECT_TRUE(model.planes[0].normal_W.isApprox(-Vector3d::UnitX(), 1e-12));
  EXPECT_NEAR(model.planes[0].gap_m, 0.002, 1e-12);
  EXPECT_EQ(model.planes[1].object, 1);
  EXPECT_TRUE(model.planes[1].normal_W.isApprox(Vector3d::UnitZ(), 1e-12));
  EXPECT_NEAR(model.planes[1].gap_m, 0.005, 1e-12);
  const LocalModel capped = Build(*tool, proxy, {floor.get(), wall.get()}, {1, 2},
                                  {.radius_m = kRadius, .max_planes = 1});
  ASSERT_EQ(capped.planes.size(), 1u);
  EXPECT_EQ(capped.planes[0].object, 2);
}

// The model does not depend on the order the obstacles come in.
TEST(LocalModelBuilderTest, ObstacleOrderDoesNotMatter) {
  const auto floor = Floor();
  const auto sphere = MakeBody(MakeIcosphere(0.05, 2), At(0.06, 0, 0.05));
  const auto tool = Tool();
  std::mt19937 rng(8);
  for (int k = 0; k < 20; ++k) {
    Isometry3d X_WP = testing_poses::RandomPose(rng, 0.02);
    X_WP.translation() += Vector3d(0, 0, 0.025);
    const LocalModel a = Build(*tool, ProxyAt(X_WP), {floor.get(), sphere.get()}, {1, 2});
    const LocalModel b = Build(*tool, ProxyAt(X_WP), {sphere.get(), floor.get()}, {2, 1});
    ASSERT_EQ(a.planes.size(), b.planes.size()) << k;
    for (size_t i = 0; i < a.planes.size(); ++i) {
      EXPECT_EQ(a.planes[i].object, b.planes[i].object) << k;
      EXPECT_EQ(a.planes[i].normal_W, b.planes[i].normal_W) << k;
      EXPECT_EQ(a.planes[i].gap_m, b.planes[i].gap_m) << k;
      EXPECT_EQ(a.planes[i].tool_point_W, b.planes[i].tool_point_W) << k;
    }
  }
}

// The model's promise, against the geometry itself: a translation of the
// tool within the radius that keeps it in front of every plane never makes
// it meet the obstacle. A turned cube over the inside of the floor's top, at
// random turns, places and gaps; translations drawn at random in the ball of
// the radius, kept when they satisfy every plane with a small slack. Over
// the floor's inside the nearest features are the floor's face and the
// tool's corners or edges. (Where they are not, beside a faceted ball's
// vertex or edge, the builder may hold no plane at all though the ball is
// within the radius: the planes are taken only where a feature's foot lies
// on the other feature.)
TEST(LocalModelBuilderTest, TranslationsThePlanesAllowMeetNothing) {
  const auto floor = Floor();
  const auto tool = Tool();
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> unit(0, 1);
  int allowed = 0;
  for (int k = 0; k < 60; ++k) {
    // A turned tool lowered until it meets the floor, then raised a
    // random gap.
    Isometry3d X_WP = testing_poses::RandomPose(rng, 0.3);
    double height = 0.05;
    auto at = [&](double z) {
      Isometry3d X = X_WP;
      X.translation().z() = z;
      return X;
    };
    while (!AnyTrianglesMeet(tool->model, at(height), std::nullopt, floor->model, floor->X_WO, 0)) {
      height -= 1e-4;
    }
    X_WP = at(height + 1e-4 + 0.8 * kRadius * unit(rng));
    const LocalModel model =
        Build(*tool, ProxyAt(X_WP), {floor.get()}, {0}, {.radius_m = kRadius, .max_planes = 64});
    ASSERT_FALSE(model.planes.empty()) << k;
    for (int j = 0; j < 200; ++j) {
      const Vector3d step =
          0.9 * kRadius * std::cbrt(unit(rng)) * testing_poses::RandomDirection(rng);
      bool in_front = true;
      for (const ConstraintPlane& plane : model.planes) {
        in_front &= plane.gap_m + plane.normal_W.dot(step) > 1e-5;
      }
      if (!in_front) continue;
      ++allowed;
      Isometry3d moved = X_WP;
      moved.translation() += step;
      ASSERT_FALSE(AnyTrianglesMeet(tool->model, moved, std::nullopt, floor->model, floor->X_WO, 0))
          << "case " << k << ", step " << step.transpose();
    }
  }
  EXPECT_GT(allowed, 1000);  // the draws reached both sides of the planes
}

// A move bounded by `margin`: a random shift and turn scaled so that
// Moved says at most the margin.
Isometry3d MoveWithin(const LocalModelPairs& pairs, std::mt19937& rng, double margin) {
  std::uniform_real_distribution<double> unit(0, 1);
  Isometry3d X = pairs.X_WP;
  if (pairs.moves == ProxyMoves::kShiftsOnly) {  // a shift alone, up to the whole margin
    X.translation() += margin * unit(rng) * testing_poses::RandomDirection(rng);
    return X;
  }
  X.translation() += 0.5 * margin * unit(rng) * testing_poses::RandomDirection(rng);
  X.linear() = X.linear() * Eigen::AngleAxisd(0.5 * margin / pairs.lever_m * unit(rng),
                                              testing_poses::RandomDirection(rng))
                                .toRotationMatrix();
  return X;
}

// The pairs' promise: wherever the proxy moves within the margin, the
// model made from the pairs gathered before is the one a fresh search
// there makes, plane for plane and bit for bit (the same tests on the same
// numbers); pairs gathered short of the radius make it too, or say they
// cannot. A turned cube over a floor and beside a faceted ball, random
// gather poses and moves (with turns, and shifts alone for the pairs
// gathered for those), with and without a cap on the planes, searches for
// the whole radius and for half of it.
TEST(LocalModelBuilderTest, ModelsFromPairsAreTheSearchesWithinTheMargin) {
  const auto floor = Floor();
  const auto ball = MakeBody(MakeIcosphere(0.03, 2), At(0.035, 0, 0.03));
  const auto tool = Tool();
  const std::vector<PosedObject> posed{floor->posed(), ball->posed()};
  const std::vector<ObjectId> ids{1, 2};
  std::mt19937 rng(23);
  int planes = 0;
  int short_served = 0, short_refused = 0;
  for (const auto& [max_planes, reach] :
       {std::pair{16, kRadius}, {64, kRadius}, {16, kRadius / 2}, {64, kRadius / 2}}) {
    const LocalModelOptions options{.radius_m = kRadius, .max_planes = max_planes};
    for (int k = 0; k < 40; ++k) {
      Isometry3d X_WP = testing_poses::RandomPose(rng, 0.02);
      X_WP.translation() += Vector3d(0, 0, 0.018);
      LocalModelPairs pairs;
      const double margin = 0.25 * kRadius;
      const ProxyMoves moves = k % 2 == 0 ? ProxyMoves::kAny : ProxyMoves::kShiftsOnly;
      GatherLocalModelPairs(tool->posed(), X_WP, posed, ids, options, margin, reach, moves, pairs);
      for (int j = 0; j < 20; ++j) {
        const Isometry3d moved = MoveWithin(pairs, rng, margin);
        ASSERT_LE(pairs.Moved(moved), margin);
        const Vector3d p_WD = moved.translation() - Vector3d(0, 0, 0.001);
        LocalModel from_pairs, searched;
        const bool served =
            ModelFromPairs(tool->object, ProxyAt(moved), p_WD, pairs, options, from_pairs);
        if (reach == kRadius) {
          ASSERT_TRUE(served);
        } else {
          ++(served ? short_served : short_refused);
          if (!served) continue;
        }
        BuildLocalModel(tool->posed(), ProxyAt(moved), p_WD, posed, ids, options, searched);
        ASSERT_EQ(from_pairs.planes.size(), searched.planes.size()) << k << " " << j;
        planes += static_cast<int>(searched.planes.size());
        for (size_t i = 0; i < searched.planes.size(); ++i) {
          const ConstraintPlane &a = from_pairs.planes[i], &b = searched.planes[i];
          EXPECT_EQ(a.object, b.object);
          EXPECT_EQ(a.normal_W, b.normal_W);
          EXPECT_EQ(a.gap_m, b.gap_m);
          EXPECT_EQ(a.point_W, b.point_W);
          EXPECT_EQ(a.tool_point_W, b.tool_point_W);
          EXPECT_EQ(a.stiffness_n_per_m, b.stiffness_n_per_m);
        }
        EXPECT_TRUE(from_pairs.X_WP.isApprox(searched.X_WP, 0.0));
        EXPECT_EQ(from_pairs.p_WD, searched.p_WD);
        EXPECT_EQ(from_pairs.validity_radius_m, searched.validity_radius_m);
      }
    }
  }
  EXPECT_GT(planes, 2000);  // the poses came within the radius of both
  // Both answers of the short searches were met.
  EXPECT_GT(short_served, 100) << short_refused;
  EXPECT_GT(short_refused, 100);
}

// A plane of the brute-force oracle below: its normal and a point on it.
struct OraclePlane {
  Vector3d normal_W, point_W;
};

// The brute-force oracle: the planes every pair of features of `tool` at
// X_WP and `object` gives, by the definition BuildLocalModel documents
// (every tool vertex over every object face, every object vertex under
// every tool face, every tool edge against every object edge: the pair
// would meet moving along the plane's normal, in front by at most
// `radius`, behind by at most `behind`). `tolerance` > 0 asks for the pairs
// that pass with that much room on every test (relative: of an edge's
// length, of a unit normal), < 0 for those that pass with that much
// allowance: the builder's own rounding lies between.
std::vector<OraclePlane> AllPairsPlanes(const Body& tool, const Isometry3d& X_WP,
                                        const Body& object, double radius, double behind,
                                        double tolerance) {
  const HapticObject &t = tool.object, &o = object.object;
  auto place = [](const HapticObject& h, const Isometry3d& X, VertexId v) {
    return Vector3d(X * h.position(v));
  };
  auto normal = [&](const HapticObject& h, const Isometry3d& X, FaceId f) {
    const Face& face = h.face(f);
    const Vector3d a = place(h, X, face.vertices[0]), b = place(h, X, face.vertices[1]),
                   c = place(h, X, face.vertices[2]);
    return Vector3d((b - a).cross(c - a).normalized());
  };
  // Whether `p`, on the plane of face f, is inside it (by the tolerance).
  auto inside = [&](const HapticObject& h, const Isometry3d& X, FaceId f, const Vector3d& p) {
    const Face& face = h.face(f);
    const Vector3d n = normal(h, X, f);
    for (int i = 0; i < 3; ++i) {
      const Vector3d from = place(h, X, face.vertices[i]);
      const Vector3d edge = place(h, X, face.vertices[(i + 1) % 3]) - from;
      if (n.cross(edge).dot(p - from) < tolerance * edge.squaredNorm()) return false;
    }
    return true;
  };
  auto in_range = [&](double gap) {
    const double room = std::abs(tolerance) * radius;
    return tolerance > 0 ? gap >= -behind + room && gap <= radius - room
                         : gap >= -behind - room && gap <= radius + room;
  };
  std::vector<OraclePlane> planes;
  // A vertex `p` over face f of `h` at X: the face's plane, turned round
  // when the face is the tool's.
  auto vertex_face = [&](const HapticObject& h, const Isometry3d& X, FaceId f, const Vector3d& p,
                         bool tool_face) {
    const Vector3d n = normal(h, X, f);
    if (!n.allFinite()) return;
    const double gap = n.dot(p - place(h, X, h.face(f).vertices[0]));
    if (!in_range(gap) || !inside(h, X, f, p - gap * n)) return;
    planes.push_back({tool_face ? Vector3d(-n) : n, tool_face ? p : Vector3d(p - gap * n)});
  };
  for (VertexId v = 0; v < t.num_vertices(); ++v) {
    for (FaceId f = 0; f < o.num_faces(); ++f)
      vertex_face(o, object.X_WO, f, place(t, X_WP, v), false);
  }
  for (VertexId v = 0; v < o.num_vertices(); ++v) {
    for (FaceId f = 0; f < t.num_faces(); ++f)
      vertex_face(t, X_WP, f, place(o, object.X_WO, v), true);
  }
  auto out = [&](const HapticObject& h, const Isometry3d& X, EdgeId e) {
    Vector3d sum = Vector3d::Zero();
    for (const FaceId f : h.EdgeFaces(e)) sum += normal(h, X, f);
    return sum;
  };
  for (EdgeId i = 0; i < t.num_edges(); ++i) {
    const Vector3d t0 = place(t, X_WP, t.edge(i).vertices[0]),
                   t1 = place(t, X_WP, t.edge(i).vertices[1]), t_out = out(t, X_WP, i);
    for (EdgeId j = 0; j < o.num_edges(); ++j) {
      const Vector3d o0 = place(o, object.X_WO, o.edge(j).vertices[0]),
                     o1 = place(o, object.X_WO, o.edge(j).vertices[1]),
                     o_out = out(o, object.X_WO, j);
      const Vector3d u = t1 - t0, v = o1 - o0;
      // Parallel edges give no plane of their own (their ends' pairs do);
      // within the tolerance of parallel the oracle asks nothing.
      const Vector3d cross = u.cross(v);
      if (!(cross.norm() > std::max(tolerance, 1e-10) * u.norm() * v.norm())) continue;
      // The lines' closest points, which must lie on both edges.
      const Vector3d w = t0 - o0;
      const double det = u.dot(u) * v.dot(v) - u.dot(v) * u.dot(v);
      const double a = (u.dot(v) * v.dot(w) - v.dot(v) * u.dot(w)) / det;
      const double b = (u.dot(u) * v.dot(w) - u.dot(v) * u.dot(w)) / det;
      if (a < tolerance || a > 1 - tolerance || b < tolerance || b > 1 - tolerance) continue;
      const Vector3d on_tool = t0 + a * u, on_object = o0 + b * v;
      // Out of the object and into the tool: either sign of the normal
      // that does both (within the tolerance).
      for (const double sign : {1.0, -1.0}) {
        const Vector3d n = sign * cross.normalized();
        if (!(n.dot(o_out) > tolerance * o_out.norm() &&
              n.dot(t_out) < -tolerance * t_out.norm())) {
          continue;
        }
        if (in_range(n.dot(on_tool - on_object))) planes.push_back({n, on_object});
      }
    }
  }
  return planes;
}

// Whether `planes` holds one that is `plane` (the builder's own
// criterion: normals within 1e-9 in cosine, offsets within 1e-9 of the
// tool's size; the oracle computes in another order, rounding ~1e-16).
bool Holds(const std::vector<ConstraintPlane>& planes, const OraclePlane& plane, double size) {
  return std::any_of(planes.begin(), planes.end(), [&](const ConstraintPlane& p) {
    return p.normal_W.dot(plane.normal_W) > 1 - 1e-9 &&
           std::abs(p.normal_W.dot(p.point_W - plane.point_W)) <= 1e-9 * size;
  });
}

// Against the brute-force oracle: wherever the proxy moves within the
// search's margin, the model made from the pairs gathered before holds
// every plane that any pair of features of the tool and the object gives
// there, and no other (no cap on the planes). A coarse ring tool through a
// coarse ring (every kind of pair, many edge pairs) and a turned cube over
// a faceted ball, at random gather poses near the object and random moves
// within the margin.
TEST(LocalModelBuilderTest, ModelsFromPairsHoldEveryPlaneOfAllPairs) {
  const auto ring = MakeBody(MakeTorus(0.05, 0.008, 24, 8));
  const auto hook = MakeBody(MakeTorus(0.05, 0.008, 24, 8));
  const auto ball = MakeBody(MakeIcosphere(0.03, 2), At(0, 0, -0.03));
  const auto cube = Tool();
  struct Case {
    const Body* tool;
    const Body* object;
    Isometry3d X_WP;  // the middle of the gather poses
    double spread;    // how far from it they go
  };
  // The hook standing through the ring, its inside touching the ring's
  // tube at +x; the cube resting on the ball's top.
  Isometry3d through = Isometry3d::Identity();
  through.linear() = Eigen::AngleAxisd(std::numbers::pi / 2, Vector3d::UnitX()).toRotationMatrix();
  through.translation() = Vector3d(0.05 + 0.05 - 0.016 - 0.004, 0, 0);
  const Case cases[] = {{hook.get(), ring.get(), through, 0.004},
                        {cube.get(), ball.get(), At(0, 0, kTool / 2 + 0.003), 0.004}};
  const LocalModelOptions options{.radius_m = kRadius, .max_planes = 1 << 20};
  std::mt19937 rng(31);
  int oracle_planes = 0;
  for (const Case& c : cases) {
    const std::vector<PosedObject> posed{c.object->posed()};
    const std::vector<ObjectId> ids{7};
    const double size = c.tool->object.bounding_box().diagonal().norm();
    const double behind = 1e-6 * size;  // the builder's stand-off allowance
    for (int k = 0; k < (hs::testing::kSanitizedBuild ? 2 : 8); ++k) {
      Isometry3d X_WP = c.X_WP;
      X_WP.translation() += c.spread * testing_poses::RandomDirection(rng);
      X_WP.linear() =
          X_WP.linear() *
          Eigen::AngleAxisd(0.05, testing_poses::RandomDirection(rng)).toRotationMatrix();
      LocalModelPairs pairs;
      const double margin = 0.15 * kRadius;
      GatherLocalModelPairs(c.tool->posed(), X_WP, posed, ids, options, margin, pairs);
      for (int j = 0; j < 3; ++j) {
        const Isometry3d moved = j == 0 ? X_WP : MoveWithin(pairs, rng, margin);
        LocalModel model;
        ModelFromPairs(c.tool->object, ProxyAt(moved), moved.translation(), pairs, options, model);
        for (const OraclePlane& plane :
             AllPairsPlanes(*c.tool, moved, *c.object, kRadius, behind, 1e-7)) {
          ++oracle_planes;
          EXPECT_TRUE(Holds(model.planes, plane, size))
              << "case " << k << " move " << j << ": missing n " << plane.normal_W.transpose()
              << " at " << plane.point_W.transpose();
        }
        const std::vector<OraclePlane> loose =
            AllPairsPlanes(*c.tool, moved, *c.object, kRadius, behind, -1e-7);
        for (const ConstraintPlane& plane : model.planes) {
          std::vector<ConstraintPlane> one{plane};
          EXPECT_TRUE(std::any_of(loose.begin(), loose.end(),
                                  [&](const OraclePlane& p) { return Holds(one, p, size); }))
              << "case " << k << " move " << j << ": no pair gives n " << plane.normal_W.transpose()
              << " at " << plane.point_W.transpose();
        }
      }
    }
  }
  // The poses came within the radius (a quarter of them under a sanitizer).
  EXPECT_GT(oracle_planes, hs::testing::kSanitizedBuild ? 250 : 1000);
}

// Moved bounds the move of any point the pairs hold: a shift counts its
// length, a turn its angle times the lever (the tool's reach plus the
// radius and the margin, times sqrt 3: hand-computed for the 2 cm cube,
// whose farthest corner is sqrt(3) cm from its centre).
TEST(LocalModelBuilderTest, MovedIsTheShiftPlusTheTurnTimesTheLever) {
  const auto floor = Floor();
  const auto tool = Tool();
  LocalModelPairs pairs;
  const Isometry3d X_WP = At(0, 0, 0.02);
  const std::vector<PosedObject> posed{floor->posed()};
  const std::vector<ObjectId> ids{0};
  GatherLocalModelPairs(tool->posed(), X_WP, posed, ids, {.radius_m = kRadius}, 0.002, pairs);
  EXPECT_NEAR(pairs.lever_m, std::sqrt(3.0) * (std::sqrt(3.0) * 0.01 + kRadius + 0.002), 1e-15);
  EXPECT_EQ(pairs.Moved(X_WP), 0);
  Isometry3d moved = X_WP;
  moved.translation() += Vector3d(0.003, 0, 0.004);
  moved.linear() = Eigen::AngleAxisd(0.01, Vector3d::UnitY()).toRotationMatrix();
  EXPECT_NEAR(pairs.Moved(moved), 0.005 + 0.01 * pairs.lever_m, 1e-12);
  EXPECT_FALSE(pairs.vertex_faces.empty());
  // Pairs for shifts alone: a shift is its length, any turn too far.
  GatherLocalModelPairs(tool->posed(), X_WP, posed, ids, {.radius_m = kRadius}, 0.002, kRadius,
                        ProxyMoves::kShiftsOnly, pairs);
  EXPECT_EQ(pairs.moves, ProxyMoves::kShiftsOnly);
  Isometry3d shifted = X_WP;
  shifted.translation() += Vector3d(0.003, 0, 0.004);
  EXPECT_NEAR(pairs.Moved(shifted), 0.005, 1e-15);
  EXPECT_EQ(pairs.Moved(moved), std::numeric_limits<double>::infinity());
}

}  // namespace
}  // namespace hs

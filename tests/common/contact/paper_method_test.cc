#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <optional>
#include <random>
#include <vector>

#include "common/collision/triangle_pairs.h"
#include "common/collision/triangle_sat.h"
#include "common/contact/contact_context.h"
#include "common/contact/contact_query.h"
#include "common/contact/paper_method.h"
#include "common/contact/projection_options.h"
#include "common/model/procedural.h"
#include "tests/common/random_poses.h"

namespace hs {
namespace {

using testing_poses::RandomDirection;
using testing_poses::RandomPose;

// An object with its hierarchy; heap-held so PosedObject's pointers stay put.
struct Body {
  explicit Body(MeshInput mesh)
      : object(*HapticObject::Create("body", std::move(mesh))),
        model(object, BvType::kObbRss, 1e-6 * object.bounding_box().diagonal().norm()) {}
  HapticObject object;
  CollisionModel model;
};

std::unique_ptr<Body> MakeBody(MeshInput mesh) { return std::make_unique<Body>(std::move(mesh)); }

Isometry3d At(const Vector3d& p) {
  Isometry3d X = Isometry3d::Identity();
  X.translation() = p;
  return X;
}

Isometry3d At(const Vector3d& p, double angle, const Vector3d& axis) {
  Isometry3d X = At(p);
  X.rotate(Eigen::AngleAxisd(angle, axis.normalized()));
  return X;
}

ContactSet Paper(const Body& m, const Isometry3d& X_WM, const Body& f, const Isometry3d& X_WF,
                 const Vector3d& direction_W) {
  const ContactQuery query{.direction_W = direction_W, .method = ContactMethod::kPaper2d};
  absl::StatusOr<ContactSet> set =
      ComputeContact({&m.object, &m.model, X_WM}, {&f.object, &f.model, X_WF}, query);
  EXPECT_TRUE(set.ok()) << set.status();
  return set.ok() ? *set : ContactSet{};
}

// Octahedron of circumradius r: vertex 0 +x, 1 -x, 2 +y, 3 -y, 4 +z, 5 -z.
MeshInput MakeOctahedron(double r) {
  MeshInput mesh;
  mesh.materials.push_back(Material{});
  mesh.positions = {{r, 0, 0}, {-r, 0, 0}, {0, r, 0}, {0, -r, 0}, {0, 0, r}, {0, 0, -r}};
  for (int sx : {0, 1}) {
    for (int sy : {0, 1}) {
      for (int sz : {0, 1}) {
        const VertexId x = sx, y = 2 + sy, z = 4 + sz;
        // Counter-clockwise seen from outside: each negative axis flips it.
        if ((sx + sy + sz) % 2 == 0) {
          mesh.faces.push_back(FaceInput{{x, y, z}});
        } else {
          mesh.faces.push_back(FaceInput{{x, z, y}});
        }
      }
    }
  }
  return mesh;
}

// Every face of `o` posed at X, as triangles in the same frame.
std::vector<Triangle3d> Triangles(const HapticObject& o, const Isometry3d& X) {
  std::vector<Triangle3d> out;
  for (const Face& f : o.faces()) {
    out.push_back({X * o.position(f.vertices[0]), X * o.position(f.vertices[1]),
                   X * o.position(f.vertices[2])});
  }
  return out;
}

// Oracle: the exact t* of docs/algorithm.md by brute force over all face
// pairs: the end of the union of sweep intervals that covers t = 0 (0 when
// none does). Surfaces only: it does not see a mesh wholly inside another.
double ExactDepth(const Body& m, const Isometry3d& X_WM, const Body& f, const Isometry3d& X_WF,
                  const Vector3d& direction_W) {
  const std::vector<Triangle3d> a = Triangles(m.object, X_WM), b = Triangles(f.object, X_WF);
  const Vector3d D = direction_W.normalized();
  // Seen along D, two triangles whose boxes across D are apart never meet
  // however far one slides: skips most sweeps, changes no answer.
  const Vector3d e1 = D.unitOrthogonal(), e2 = D.cross(e1);
  auto box = [&](const Triangle3d& t) {
    Eigen::AlignedBox2d bx;
    for (const Vector3d& p : t) bx.extend(Eigen::Vector2d(e1.dot(p), e2.dot(p)));
    return bx;
  };
  std::vector<Eigen::AlignedBox2d> box_a, box_b;
  for (const Triangle3d& t : a) box_a.push_back(box(t));
  for (const Triangle3d& t : b) box_b.push_back(box(t));
  std::vector<Interval> intervals;
  for (size_t i = 0; i < a.size(); ++i) {
    for (size_t j = 0; j < b.size(); ++j) {
      if (!box_a[i].intersects(box_b[j])) continue;
      const Interval in = SweptIntersection(a[i], b[j], D, 0);
      if (!in.empty() && in.hi >= 0) intervals.push_back(in);
    }
  }
  std::sort(intervals.begin(), intervals.end(),
            [](const Interval& x, const Interval& y) { return x.lo < y.lo; });
  double t = 0;
  for (const Interval& in : intervals) {
    if (in.lo > t) break;
    t = std::max(t, in.hi);
  }
  return t;
}

// Whether any face pair of the two posed objects intersects (margin 0).
bool Penetrate(const Body& m, const Isometry3d& X_WM, const Body& f, const Isometry3d& X_WF) {
  std::vector<TrianglePair> pairs;
  FindIntersectingTriangles(m.model, X_WM, f.model, X_WF, 0, pairs);
  return !pairs.empty();
}

// The tolerance ComputeContact would use: 1e-9 x the pair's size.
double PairTolerance(const Body& m, const Body& f) {
  return 1e-9 *
         (m.object.bounding_box().diagonal().norm() + f.object.bounding_box().diagonal().norm());
}

// The method on a context built by hand, F at the origin (world = F's
// frame): the BVH's pairs, or with `whole_objects` every face pair, which
// makes every vertex and edge of both objects a candidate. The pairs are
// found at the pair's default tolerance; `tolerance`, when given, is the
// one the method reconstructs at.
ContactSet RunContext(const Body& m, const Isometry3d& X_FM, const Body& f, const Vector3d& D,
                      bool whole_objects = false, const ProjectionOptions& options = {},
                      std::optional<double> tolerance = std::nullopt) {
  const double pair_tol = PairTolerance(m, f);
  const double tol = tolerance.value_or(pair_tol);
  ContactContext context{m.object, m.model, f.object, f.model, X_FM, D.normalized(), tol, {}};
  if (whole_objects) {
    for (FaceId a = 0; a < m.object.num_faces(); ++a) {
      for (FaceId b = 0; b < f.object.num_faces(); ++b) context.pairs.push_back({a, b});
    }
  } else {
    FindIntersectingTriangles(m.model, X_FM, f.model, Isometry3d::Identity(), pair_tol,
                              context.pairs);
  }
  EXPECT_FALSE(context.pairs.empty());
  ContactSet set;
  ToWorld(ReconstructByProjection(context, options), Isometry3d::Identity(), set);
  set.tolerance_m = tol;
  return set;
}

// The big fixed box of the fig. 8 scenes: 4 x 4 x 1, top face at z = 0.5.
constexpr double kTop = 0.5;
MeshInput BigBox() { return MakeBox(Vector3d(4, 4, 1)); }

// Pressing depth of the fig. 8 scenes, metres.
constexpr double kDelta = 0.01;

// Depths below are differences of O(1) coordinates after a few flops and
// two rigid transforms: rounding is ~1e-15. 1e-12 leaves a wide margin and is
// still far below the touching tolerance (1e-9 x the pair's ~6 m diagonal).
constexpr double kDepthTol = 1e-12;

std::vector<VertexId> Ids(std::initializer_list<VertexId> ids) { return ids; }

// Fig. 8 #1: a convex corner pressed into a face is a vertex contact at the analytic depth.
TEST(PaperMethodTest, Fig8VertexOnFace) {
  const auto f = MakeBody(BigBox());
  const auto m = MakeBody(MakeOctahedron(0.5));
  const Isometry3d X_WM = At({0.1, -0.2, kTop + 0.5 - kDelta});
  const ContactSet set = Paper(*m, X_WM, *f, Isometry3d::Identity(), {0, 0, -1});
  EXPECT_TRUE(set.colliding);
  EXPECT_TRUE(set.penetrating);
  EXPECT_FALSE(set.singular_case);
  EXPECT_NEAR(set.depth_m, kDelta, kDepthTol);
  EXPECT_TRUE(set.reversing_vector_W.isApprox(Vector3d(0, 0, kDelta), 1e-12));
  EXPECT_EQ(set.normal_W, Vector3d(0, 0, 1));
  EXPECT_EQ(set.moving.kind, FeatureKind::kVertex);
  EXPECT_EQ(set.moving.vertices, Ids({5}));
  EXPECT_TRUE(set.moving.edges.empty());
  // D is perpendicular to xy: only yz and xz are usable, and both see it.
  EXPECT_EQ(set.plane_depths_m[0], std::numeric_limits<double>::infinity());
  EXPECT_NEAR(set.plane_depths_m[1], kDelta, kDepthTol);
  EXPECT_NEAR(set.plane_depths_m[2], kDelta, kDepthTol);
  ASSERT_EQ(set.points.size(), 1u);
  EXPECT_EQ(set.points[0].moving, (Feature{FeatureKind::kVertex, 5}));
  EXPECT_EQ(set.points[0].fixed.kind, FeatureKind::kEdge);
  // Once separated the tip rests on the top face.
  EXPECT_TRUE(set.points[0].p_WC.isApprox(Vector3d(0.1, -0.2, kTop), 1e-12));
}

// Fig. 8 #2: a convex edge pressed into a face is an edge contact of that edge and its ends.
TEST(PaperMethodTest, Fig8EdgeOnFace) {
  const auto f = MakeBody(BigBox());
  const auto m = MakeBody(MakeBox(Vector3d::Constant(0.4)));
  // Turned 45 degrees about x, the box's lowest edge joins vertices 0 and 1
  // (y and z bits clear), 0.2 * sqrt(2) below its centre.
  const Isometry3d X_WM = At({0.1, -0.2, kTop + 0.2 * std::sqrt(2.0) - kDelta},
                             std::numbers::pi / 4, Vector3d::UnitX());
  const ContactSet set = Paper(*m, X_WM, *f, Isometry3d::Identity(), {0, 0, -1});
  EXPECT_TRUE(set.penetrating);
  EXPECT_NEAR(set.depth_m, kDelta, kDepthTol);
  EXPECT_EQ(set.moving.kind, FeatureKind::kEdge);
  EXPECT_EQ(set.moving.vertices, Ids({0, 1}));
  EXPECT_EQ(set.moving.edges, std::vector<EdgeId>{m->object.FindEdge(0, 1)});
  EXPECT_TRUE(set.moving.faces.empty());
  EXPECT_EQ(set.points.size(), 2u);
}

// Fig. 8 #3: a box pressed face-down into a bigger one is a face contact of its bottom side.
TEST(PaperMethodTest, Fig8FaceOnFace) {
  const auto f = MakeBody(BigBox());
  const auto m = MakeBody(MakeBox(Vector3d::Constant(0.4)));
  const ContactSet set =
      Paper(*m, At({0.1, -0.2, kTop + 0.2 - kDelta}), *f, Isometry3d::Identity(), {0, 0, -1});
  EXPECT_TRUE(set.penetrating);
  EXPECT_NEAR(set.depth_m, kDelta, kDepthTol);
  EXPECT_EQ(set.moving.kind, FeatureKind::kFace);
  // MakeBox lists the -z side first: faces 0 and 1 over vertices 0..3.
  EXPECT_EQ(set.moving.faces, (std::vector<FaceId>{0, 1}));
  EXPECT_EQ(set.moving.vertices, Ids({0, 1, 2, 3}));
  EXPECT_EQ(set.moving.edges.size(), 5u);  // four sides and the quad's diagonal
  EXPECT_EQ(set.points.size(), 4u);
}

// Torus of the fig. 8 #4 scene: 24 x 12 quads, so ring j = 9 of every tube
// section sits at the bottom (angle 3 pi / 2) when lying flat.
constexpr int kMajor = 24, kMinor = 12;
MeshInput Torus() { return MakeTorus(0.6, 0.15, kMajor, kMinor); }

// Fig. 8 #4: a torus pressed onto a box touches along its whole bottom ring, at the exact depth.
// Many contact vertices (all 24 of the ring), at the analytic depth that the
// brute-force oracle confirms, for straight and tilted motion.
TEST(PaperMethodTest, Fig8ManyPointsNonConvex) {
  const auto f = MakeBody(BigBox());
  const auto m = MakeBody(Torus());
  const Isometry3d X_WM = At({0.1, -0.2, kTop + 0.15 - kDelta});
  std::vector<VertexId> ring;
  for (int i = 0; i < kMajor; ++i) ring.push_back(i * kMinor + 9);

  const ContactSet set = Paper(*m, X_WM, *f, Isometry3d::Identity(), {0, 0, -1});
  EXPECT_NEAR(set.depth_m, kDelta, kDepthTol);
  EXPECT_NEAR(ExactDepth(*m, X_WM, *f, Isometry3d::Identity(), {0, 0, -1}), kDelta, kDepthTol);
  EXPECT_EQ(set.moving.vertices, ring);
  EXPECT_EQ(set.moving.edges.size(), static_cast<size_t>(kMajor));  // the ring's chords
  EXPECT_EQ(set.moving.kind, FeatureKind::kEdge);
  EXPECT_EQ(set.points.size(), ring.size());

  // Tilted motion: the ring must rise by kDelta, t* = kDelta / |D_z|; the
  // xy plane sees the torus inside the box's top and reports far more, so
  // the minimum over planes is what makes the answer right.
  const Vector3d D = Vector3d(0.2, 0.1, -1).normalized();
  const ContactSet tilted = Paper(*m, X_WM, *f, Isometry3d::Identity(), D);
  EXPECT_NEAR(tilted.depth_m, kDelta / std::abs(D.z()), kDepthTol);
  EXPECT_NEAR(ExactDepth(*m, X_WM, *f, Isometry3d::Identity(), D), kDelta / std::abs(D.z()),
              kDepthTol);
  // (Run in full: the query stops the xy plane once it cannot win.)
  const ContactSet every_plane =
      RunContext(*m, X_WM, *f, D, /*whole_objects=*/false, {.exact_plane_depths = true});
  EXPECT_EQ(every_plane.depth_m, tilted.depth_m);
  EXPECT_GT(every_plane.plane_depths_m[0], 10 * tilted.depth_m);
  EXPECT_EQ(tilted.moving.vertices, ring);
}

// The literal "inside a projected paired triangle" test misses fig. 8 #1 entirely.
// This is why the default penetration test is the paper's own d_ij >= 0
// (the plain "inside the projection" reading is the other option): with D along a
// face's normal, that face is seen edge-on in every usable plane, so no
// vertex is ever inside its projection and nothing is found.
TEST(PaperMethodTest, InsideTriangleReadingMissesFacesSeenEdgeOn) {
  const auto f = MakeBody(BigBox());
  const auto m = MakeBody(MakeOctahedron(0.5));
  const Isometry3d X_FM = At({0.1, -0.2, kTop + 0.5 - kDelta});
  const ContactSet inside = RunContext(*m, X_FM, *f, {0, 0, -1}, /*whole_objects=*/false,
                                       {.penetration = PenetrationTest::kInsideTriangle});
  EXPECT_EQ(inside.depth_m, 0);
  EXPECT_EQ(inside.moving.kind, FeatureKind::kNone);
  const ContactSet crossing = RunContext(*m, X_FM, *f, {0, 0, -1});
  EXPECT_NEAR(crossing.depth_m, kDelta, kDepthTol);
}

// ---------------------------------------------------------------------------
// Separation: moving M by the reversing vector must leave the objects apart.

// One of +-x, +-y, +-z of F's frame.
Vector3d RandomAxis(std::mt19937& rng) {
  Vector3d D = Vector3d::Zero();
  D[std::uniform_int_distribution<int>(0, 2)(rng)] =
      std::uniform_int_distribution<int>(0, 1)(rng) ? 1 : -1;
  return D;
}

// Whether M moved back by `depth` along D, plus 2 tolerances, is clear of F
// (F at the origin). The method is exact up to the tolerance, so at `depth`
// the objects may still touch within it, which margin 0 counts; 2 more
// tolerances part a touching pair and leave any real overlap.
bool SeparatedAfter(const Body& m, const Isometry3d& X_FM, const Body& f, const Vector3d& D,
                    double depth, double tol) {
  return !Penetrate(m, At(-(depth + 2 * tol) * D) * X_FM, f, Isometry3d::Identity());
}

// M moved along D so that its exact depth is `depth`: one haptic step of
// motion into contact. nullopt when the pose is shallower than that.
std::optional<Isometry3d> AtExactDepth(const Body& m, const Isometry3d& X_FM, const Body& f,
                                       const Vector3d& D, double depth) {
  const double exact = ExactDepth(m, X_FM, f, Isometry3d::Identity(), D);
  if (exact < depth) return std::nullopt;
  return At(-(exact - depth) * D) * X_FM;
}

// With every vertex and edge as candidates the reversing vector always separates.
// Even for deep, non-convex, intertwined poses: the projection argument is
// sound. After moving by d_plane, on the line along u_p through any vertex
// the other object's projection lies wholly on the far side of it; a 2D
// overlap would have an extreme vertex (or the end of an edge bounding it)
// violating that, so the 2D projections are disjoint, hence the 3D objects.
// What breaks separation in production is the pair-local candidate set: on
// these deep random poses it separates only 3 of 40 tori and 11 of 40
// sphere-box poses.
TEST(PaperMethodTest, WholeObjectCandidatesAlwaysSeparate) {
  const auto t1 = MakeBody(MakeTorus(1.0, 0.3, 24, 12)),
             t2 = MakeBody(MakeTorus(0.8, 0.25, 24, 12));
  const auto sphere = MakeBody(MakeIcosphere(0.6, 2));
  const auto box = MakeBody(MakeBox(Vector3d(1.2, 0.8, 0.6)));
  std::mt19937 rng(41);
  for (const auto& [m, f] : {std::pair{t1.get(), t2.get()}, std::pair{sphere.get(), box.get()}}) {
    int poses = 0, local_separated = 0;
    for (int i = 0; i < 40; ++i) {
      const Isometry3d X_FM = RandomPose(rng, 0.5);
      const Vector3d D = RandomDirection(rng);
      if (!Penetrate(*m, X_FM, *f, Isometry3d::Identity())) continue;
      ++poses;
      const ContactSet whole = RunContext(*m, X_FM, *f, D, /*whole_objects=*/true);
      EXPECT_TRUE(SeparatedAfter(*m, X_FM, *f, D, whole.depth_m, whole.tolerance_m)) << i;
      const ContactSet local = RunContext(*m, X_FM, *f, D);
      local_separated += SeparatedAfter(*m, X_FM, *f, D, local.depth_m, local.tolerance_m);
    }
    EXPECT_GT(poses, 30);
    // Deep random poses: the pair-local production method fails on many.
    EXPECT_LT(local_separated, poses);
  }
}

// The same singular flag, features and contact points, bit for bit.
void ExpectSameFeatures(const ContactSet& fast, const ContactSet& every, size_t scene) {
  EXPECT_EQ(fast.singular_case, every.singular_case) << scene;
  for (const auto& [a, b] :
       {std::pair{&fast.moving, &every.moving}, std::pair{&fast.fixed, &every.fixed}}) {
    EXPECT_EQ(a->kind, b->kind) << scene;
    EXPECT_EQ(a->vertices, b->vertices) << scene;
    EXPECT_EQ(a->edges, b->edges) << scene;
    EXPECT_EQ(a->faces, b->faces) << scene;
  }
  ASSERT_EQ(fast.points.size(), every.points.size()) << scene;
  for (size_t k = 0; k < fast.points.size(); ++k) {
    EXPECT_EQ(fast.points[k].p_WC, every.points[k].p_WC) << scene;
    EXPECT_EQ(fast.points[k].moving, every.points[k].moving) << scene;
    EXPECT_EQ(fast.points[k].fixed, every.points[k].fixed) << scene;
  }
}

// Skipping the crossings that cannot reach the deepest, and stopping the
// planes that cannot change the answer, are speed-ups only: on random deep
// poses of non-convex and convex pairs, every field of the answer is what
// computing every crossing of every plane gives, except the depths of the
// planes stopped early, which are lower bounds no further than the
// tolerance under the depth.
TEST(PaperMethodTest, SkippingShallowCrossingsKeepsTheAnswer) {
  const auto t1 = MakeBody(MakeTorus(1.0, 0.3, 24, 12)),
             t2 = MakeBody(MakeTorus(0.8, 0.25, 24, 12));
  const auto sphere = MakeBody(MakeIcosphere(0.6, 2));
  const auto box = MakeBody(MakeBox(Vector3d(1.2, 0.8, 0.6)));
  const auto big_box = MakeBody(BigBox());
  const auto ring = MakeBody(Torus());
  struct Scene {
    const Body* m;
    const Body* f;
    Isometry3d X_FM;
    Vector3d D;
  };
  // Fig. 8 (d) with D along and off an axis: many edges project onto one
  // line, so crossings tie and the lowest edge must win either way.
  std::vector<Scene> scenes = {
      {ring.get(), big_box.get(), At({0.1, -0.2, kTop + 0.15 - kDelta}), {0, 0, -1}},
      {ring.get(), big_box.get(), At({0.1, -0.2, kTop + 0.15 - kDelta}), {0.2, 0.1, -1}}};
  std::mt19937 rng(42);
  for (const auto& [m, f] : {std::pair{t1.get(), t2.get()}, std::pair{sphere.get(), box.get()}}) {
    for (int i = 0; i < 40; ++i) {
      const Isometry3d X_FM = RandomPose(rng, 0.5);
      const Vector3d D = RandomDirection(rng);
      if (Penetrate(*m, X_FM, *f, Isometry3d::Identity())) scenes.push_back({m, f, X_FM, D});
    }
  }
  ASSERT_GT(scenes.size(), 60u);
  int undercut = 0;  // scenes where the preferred plane is not the one chosen
  for (size_t i = 0; i < scenes.size(); ++i) {
    const Scene& s = scenes[i];
    const double tol = PairTolerance(*s.m, *s.f);
    const ContactSet fast = RunContext(*s.m, s.X_FM, *s.f, s.D);
    const ContactSet every =
        RunContext(*s.m, s.X_FM, *s.f, s.D, /*whole_objects=*/false,
                   {.skip_shallow_crossings = false, .exact_plane_depths = true});
    EXPECT_FALSE(fast.points.empty()) << i;
    EXPECT_EQ(fast.depth_m, every.depth_m) << i;
    for (int p = 0; p < 3; ++p) {
      if (fast.plane_depths_m[p] == every.plane_depths_m[p]) continue;
      EXPECT_LT(fast.plane_depths_m[p], every.plane_depths_m[p]) << i;
      EXPECT_LE(fast.depth_m, fast.plane_depths_m[p] + tol) << i;
    }
    // The plane where D projects longest that found anything.
    const Vector3d d = s.D.normalized();
    const double projected[3] = {d.head<2>().norm(), d.tail<2>().norm(),
                                 Eigen::Vector2d(d.x(), d.z()).norm()};
    int preferred = -1;
    for (int p = 0; p < 3; ++p) {
      if (std::isinf(every.plane_depths_m[p])) continue;
      if (preferred < 0 || projected[p] > projected[preferred]) preferred = p;
    }
    ASSERT_GE(preferred, 0) << i;
    undercut += every.plane_depths_m[preferred] > every.depth_m + tol;
    ExpectSameFeatures(fast, every, i);
  }
  // Some scenes take the path where a later plane undercuts the preferred one.
  EXPECT_GT(undercut, 0);
}

// A plane stopped early is run in full when a later plane undercuts the
// preferred one, since it may then be the one chosen. Rare at the default
// tolerance, so here the tolerance is also set from the gap between two
// planes' exact depths, making one undercut the other by one to two
// tolerances; and at zero tolerance, planes that see the same contact tie
// to within a rounding: the answer is still the one every plane run in
// full gives.
TEST(PaperMethodTest, PlanesStoppedEarlyKeepTheAnswerAtAnyTolerance) {
  const auto t1 = MakeBody(MakeTorus(1.0, 0.3, 24, 12)),
             t2 = MakeBody(MakeTorus(0.8, 0.25, 24, 12));
  const ProjectionOptions exact{.skip_shallow_crossings = false, .exact_plane_depths = true};
  auto run = [&](const Isometry3d& X_FM, const Vector3d& D, double tol,
                 const ProjectionOptions& options) {
    return RunContext(*t1, X_FM, *t2, D, /*whole_objects=*/false, options, tol);
  };
  std::mt19937 rng(7);
  int compared = 0;
  auto compare = [&](const Isometry3d& X_FM, const Vector3d& D, double tol, int i) {
    const ContactSet fast = run(X_FM, D, tol, {});
    const ContactSet every = run(X_FM, D, tol, exact);
    EXPECT_EQ(fast.depth_m, every.depth_m) << i;
    ExpectSameFeatures(fast, every, i);
    ++compared;
  };
  for (int i = 0; i < 80; ++i) {
    const Isometry3d X_FM = RandomPose(rng, 0.5);
    // Every fourth direction a hair off an axis, where two planes tie.
    const Vector3d D = i % 4 == 0 ? Vector3d(1e-9, 1e-5, -1).normalized() : RandomDirection(rng);
    if (!Penetrate(*t1, X_FM, *t2, Isometry3d::Identity())) continue;
    compare(X_FM, D, 0, i);
    const ContactSet reference = run(X_FM, D, PairTolerance(*t1, *t2), exact);
    for (int p = 0; p < 3; ++p) {
      for (int q = 0; q < 3; ++q) {
        const double gap = reference.plane_depths_m[p] - reference.plane_depths_m[q];
        if (!(gap > 0 && std::isfinite(gap))) continue;
        for (const double fraction : {0.55, 0.75, 0.95}) compare(X_FM, D, fraction * gap, i);
      }
    }
  }
  EXPECT_GT(compared, 300);
}

// Shallow contacts of convex pairs are never under-estimated and always separated.
// Shallow: one step of 1 cm into objects ~1 m across, less than their faces
// are wide, so every face holding a deepest point still crosses the other's
// surface and the local candidates see it; for convex pairs any t >= t*
// separates. (At 5 cm, 13 of 288 sphere-box poses are under-estimated.)
TEST(PaperMethodTest, SeparatesShallowConvexContacts) {
  const auto sphere = MakeBody(MakeIcosphere(0.6, 2));
  const auto box = MakeBody(MakeBox(Vector3d(1.2, 0.8, 0.6)));
  constexpr double kStep = 0.01;
  std::mt19937 rng(42);
  for (const auto& [m, f] : {std::pair{sphere.get(), box.get()}, std::pair{box.get(), box.get()},
                             std::pair{sphere.get(), sphere.get()}}) {
    int poses = 0;
    for (int i = 0; i < 100; ++i) {
      const Isometry3d X = RandomPose(rng, 0.5);
      const Vector3d D = RandomDirection(rng);
      if (!Penetrate(*m, X, *f, Isometry3d::Identity())) continue;
      const std::optional<Isometry3d> X_FM = AtExactDepth(*m, X, *f, D, kStep);
      if (!X_FM) continue;
      ++poses;
      const ContactSet set = RunContext(*m, *X_FM, *f, D);
      EXPECT_GE(set.depth_m, kStep - set.tolerance_m) << i;
      EXPECT_TRUE(SeparatedAfter(*m, *X_FM, *f, D, set.depth_m, set.tolerance_m)) << i;
    }
    EXPECT_GT(poses, 80);
  }
}

// Shallow non-convex contacts separate on at least 99% of poses; the rest overshoot.
// Those few are over-estimates, not misses: for non-convex objects the set
// of separating t is not [t*, inf) but has gaps, and the paper's conservative
// max over every crossed edge can overshoot t* into the next overlap.
// Measured with this seed: 3 of 1000 poses (12 of 3000), all overshoots.
TEST(PaperMethodTest, ShallowNonConvexContactsSeparateButForRareOvershoots) {
  const auto t1 = MakeBody(MakeTorus(1.0, 0.3, 24, 12)),
             t2 = MakeBody(MakeTorus(0.8, 0.25, 24, 12));
  constexpr double kStep = 0.01;
  std::mt19937 rng(43);
  int poses = 0, separated = 0;
  for (int i = 0; i < 1000; ++i) {
    const Isometry3d X = RandomPose(rng, 0.5);
    const Vector3d D = RandomAxis(rng);
    if (!Penetrate(*t1, X, *t2, Isometry3d::Identity())) continue;
    const std::optional<Isometry3d> X_FM = AtExactDepth(*t1, X, *t2, D, kStep);
    if (!X_FM) continue;
    ++poses;
    const ContactSet set = RunContext(*t1, *X_FM, *t2, D);
    EXPECT_GE(set.depth_m, kStep - set.tolerance_m) << i;
    if (SeparatedAfter(*t1, *X_FM, *t2, D, set.depth_m, set.tolerance_m)) {
      ++separated;
      continue;
    }
    EXPECT_GT(set.depth_m, kStep + set.tolerance_m) << i;
    const ContactSet whole = RunContext(*t1, *X_FM, *t2, D, /*whole_objects=*/true);
    EXPECT_TRUE(SeparatedAfter(*t1, *X_FM, *t2, D, whole.depth_m, whole.tolerance_m)) << i;
  }
  EXPECT_GT(poses, 900);
  EXPECT_GE(separated, poses - poses / 100);
}

// Counterexample: for non-convex pairs backing out past t* can land in another overlap.
// Pose 313 of the test above: two tori 1 cm deep along +y; the paper backs
// M out by 4.3 cm, past t* and into a second overlap of the tori, so its
// reversing vector does not separate while t* does.
TEST(PaperMethodTest, NonConvexOvershootCounterexample) {
  const auto t1 = MakeBody(MakeTorus(1.0, 0.3, 24, 12)),
             t2 = MakeBody(MakeTorus(0.8, 0.25, 24, 12));
  const Isometry3d X_FM =
      At({0.30366984896863591, -0.23828174051137829, 0.48189571969172362}, 0.50796619547419464,
         {0.43805654418027623, 0.34662772417390475, 0.82943094042533361});
  const Vector3d D = Vector3d::UnitY();
  const ContactSet set = RunContext(*t1, X_FM, *t2, D);
  const double tol = set.tolerance_m;
  // The placement made t* 1 cm up to rounding of the pose's 17 digits.
  EXPECT_NEAR(ExactDepth(*t1, X_FM, *t2, Isometry3d::Identity(), D), 0.01, 1e-9);
  EXPECT_TRUE(SeparatedAfter(*t1, X_FM, *t2, D, 0.01, tol));
  EXPECT_NEAR(set.depth_m, 0.0435, 1e-4);
  EXPECT_FALSE(SeparatedAfter(*t1, X_FM, *t2, D, set.depth_m, tol));
}

// Counterexample: a contact deeper than the faces are wide is under-estimated.
// A sphere pressed 30 cm into a face: its deepest vertices belong to faces
// wholly inside the box, in no intersecting pair, so the local candidates
// stop at the ring of faces crossing the surface: 12 cm instead of 30 cm.
// With every face as a candidate the method finds the exact 30 cm.
TEST(PaperMethodTest, DeepContactIsUnderestimatedByLocalCandidates) {
  const auto f = MakeBody(BigBox());
  const auto m = MakeBody(MakeIcosphere(0.6, 2));
  const Isometry3d X_FM = At({0.1, -0.2, kTop + 0.6 - 0.3});
  const Vector3d D(0, 0, -1);
  const double exact = ExactDepth(*m, X_FM, *f, Isometry3d::Identity(), D);
  const ContactSet local = RunContext(*m, X_FM, *f, D);
  EXPECT_LT(local.depth_m, exact - 0.05);
  EXPECT_FALSE(SeparatedAfter(*m, X_FM, *f, D, local.depth_m, local.tolerance_m));
  const ContactSet whole = RunContext(*m, X_FM, *f, D, /*whole_objects=*/true);
  EXPECT_NEAR(whole.depth_m, exact, 1e-9);
  EXPECT_TRUE(SeparatedAfter(*m, X_FM, *f, D, whole.depth_m, whole.tolerance_m));
}

// ---------------------------------------------------------------------------
// Invariance.

void ExpectSameSide(const SideContact& a, const SideContact& b) {
  EXPECT_EQ(a.kind, b.kind);
  EXPECT_EQ(a.vertices, b.vertices);
  EXPECT_EQ(a.edges, b.edges);
  EXPECT_EQ(a.faces, b.faces);
}

// Same depth (within `tol`) and the same features.
void ExpectSameContact(const ContactSet& a, const ContactSet& b, double tol) {
  EXPECT_NEAR(a.depth_m, b.depth_m, tol);
  for (int p = 0; p < 3; ++p) {
    if (std::isinf(a.plane_depths_m[p])) {
      EXPECT_EQ(a.plane_depths_m[p], b.plane_depths_m[p]);
    } else {
      EXPECT_NEAR(a.plane_depths_m[p], b.plane_depths_m[p], tol);
    }
  }
  EXPECT_EQ(a.penetrating, b.penetrating);
  EXPECT_EQ(a.singular_case, b.singular_case);
  ExpectSameSide(a.moving, b.moving);
  ExpectSameSide(a.fixed, b.fixed);
  ASSERT_EQ(a.points.size(), b.points.size());
  for (size_t i = 0; i < a.points.size(); ++i) {
    EXPECT_EQ(a.points[i].moving, b.points[i].moving);
    EXPECT_EQ(a.points[i].fixed, b.points[i].fixed);
  }
}

// The fig. 8 #4 scene with tilted motion, F at a generic world pose.
struct TorusScene {
  std::unique_ptr<Body> f = MakeBody(BigBox());
  std::unique_ptr<Body> m = MakeBody(Torus());
  Isometry3d X_WF = At({0.3, -0.1, 0.2}, 0.7, {1, -2, 0.5});
  Isometry3d X_WM = X_WF * At({0.1, -0.2, kTop + 0.15 - kDelta});
  Vector3d D_W = X_WF.linear() * Vector3d(0.2, 0.1, -1).normalized();
};

// Translating the whole scene 4e5 m from the origin changes neither depth nor features.
// The method works in F's frame, where the scene is the same.
TEST(PaperMethodTest, InvariantUnderTranslatingTheSceneFarAway) {
  const TorusScene s;
  const ContactSet near = Paper(*s.m, s.X_WM, *s.f, s.X_WF, s.D_W);
  const Isometry3d T = At({1e5, -2e5, 3e5});
  const ContactSet far = Paper(*s.m, T * s.X_WM, *s.f, T * s.X_WF, s.D_W);
  // Poses 4e5 m from the origin carry ~4e5 x 2.2e-16 ~ 1e-10 m of rounding
  // into X_FM; 1e-9 covers it and is 1e-7 of the depth.
  ExpectSameContact(near, far, 1e-9);
  EXPECT_NEAR(near.depth_m, kDelta / std::abs(Vector3d(0.2, 0.1, -1).normalized().z()), 1e-9);
  for (size_t i = 0; i < near.points.size(); ++i) {
    EXPECT_LT((far.points[i].p_WC - T.translation() - near.points[i].p_WC).norm(), 1e-9);
  }
}

// Meshes whose own coordinates are 4e5 m from F's origin give the same contact.
// Here the translation is baked into both meshes, so F's frame coordinates
// themselves are large; the method subtracts a point near the contact before
// its 2D cross products, so only the input rounding (~1e-10 m) remains.
TEST(PaperMethodTest, InvariantForMeshesFarFromTheirOrigin) {
  const TorusScene s;
  const ContactSet near = Paper(*s.m, s.X_WM, *s.f, s.X_WF, s.D_W);
  const Isometry3d T = At({1e5, -2e5, 3e5});
  const auto f_far = MakeBody(TransformMesh(BigBox(), T));
  const auto m_far = MakeBody(TransformMesh(Torus(), T));
  // Posed at X * T^-1, each mesh is where it was in the world; in F's frame
  // every coordinate is shifted by T.
  const Isometry3d X_WM_far = s.X_WM * T.inverse();
  const ContactSet far = Paper(*m_far, X_WM_far, *f_far, s.X_WF * T.inverse(), s.D_W);
  ExpectSameContact(near, far, 1e-9);
}

// Rotating both objects and the motion together changes neither depth nor features.
// F's frame, hence every projection plane, turns with F, so the F-frame
// problem is the same; only the world-frame vectors turn.
TEST(PaperMethodTest, InvariantUnderRotatingTheWholeScene) {
  const TorusScene s;
  const ContactSet before = Paper(*s.m, s.X_WM, *s.f, s.X_WF, s.D_W);
  const Isometry3d Q = At(Vector3d::Zero(), 2.1, {0.3, -1, 0.4});
  const ContactSet after = Paper(*s.m, Q * s.X_WM, *s.f, Q * s.X_WF, Q.linear() * s.D_W);
  // Same F-frame inputs up to a few roundings of O(1) numbers.
  ExpectSameContact(before, after, kDepthTol);
  EXPECT_LT((after.direction_W - Q.linear() * before.direction_W).norm(), 1e-12);
  EXPECT_LT((after.reversing_vector_W - Q.linear() * before.reversing_vector_W).norm(), 1e-12);
}

// Rotating the geometry within F's frame changes the paper's depth (not the exact one).
// Here F's mesh itself is rotated, and M and D with it. The projection
// planes are F's axes: a face seen edge-on in yz and xz gave the exact 1 cm;
// turned, it is seen at a slant in every plane and each vertex is backed out
// past the far side of the projected face instead: 18.9 cm (planes xy
// 10.7 m, yz 56.9 cm, xz 18.9 cm). Still conservative: the pair is convex.
TEST(PaperMethodTest, NotInvariantUnderRotatingGeometryWithinF) {
  const Isometry3d Q = At(Vector3d::Zero(), 0.4, {1, 2, 3});
  const auto f = MakeBody(BigBox());
  const auto f_turned = MakeBody(TransformMesh(BigBox(), Q));
  const auto m = MakeBody(MakeBox(Vector3d::Constant(0.4)));
  const Isometry3d X_FM = At({0.1, -0.2, kTop + 0.2 - kDelta});
  const Vector3d D(0, 0, -1);
  const ContactSet aligned = Paper(*m, X_FM, *f, Isometry3d::Identity(), D);
  const ContactSet turned = Paper(*m, Q * X_FM, *f_turned, Isometry3d::Identity(), Q.linear() * D);
  EXPECT_NEAR(aligned.depth_m, kDelta, kDepthTol);
  EXPECT_NEAR(ExactDepth(*m, Q * X_FM, *f_turned, Isometry3d::Identity(), Q.linear() * D), kDelta,
              1e-12);
  EXPECT_GT(turned.depth_m, 10 * kDelta);
  EXPECT_TRUE(
      SeparatedAfter(*m, Q * X_FM, *f_turned, Q.linear() * D, turned.depth_m, turned.tolerance_m));
}

// ---------------------------------------------------------------------------
// Hard cases.

// Exactly touching coplanar faces: colliding, not penetrating, depth 0, face contact.
TEST(PaperMethodTest, TouchingCoplanarFaces) {
  const auto f = MakeBody(BigBox());
  const auto m = MakeBody(MakeBox(Vector3d::Constant(0.4)));
  const ContactSet set =
      Paper(*m, At({0.1, -0.2, kTop + 0.2}), *f, Isometry3d::Identity(), {0, 0, -1});
  EXPECT_TRUE(set.colliding);
  EXPECT_FALSE(set.penetrating);
  EXPECT_LE(set.depth_m, set.tolerance_m);
  EXPECT_EQ(set.moving.kind, FeatureKind::kFace);
  EXPECT_EQ(set.moving.faces, (std::vector<FaceId>{0, 1}));
}

// Motion parallel to coplanar overlapping faces gives the push depth and a face contact.
// Tops flush, M pushed sideways into F's side: the edges of the coplanar
// faces run along the projected motion in xz and count by their endpoints.
TEST(PaperMethodTest, MotionParallelToCoplanarFaces) {
  const auto f = MakeBody(BigBox());
  const auto m = MakeBody(MakeBox(Vector3d::Constant(0.4)));
  const ContactSet set =
      Paper(*m, At({2 + 0.2 - kDelta, -0.2, kTop - 0.2}), *f, Isometry3d::Identity(), {-1, 0, 0});
  EXPECT_NEAR(set.depth_m, kDelta, kDepthTol);
  EXPECT_EQ(set.plane_depths_m[1], std::numeric_limits<double>::infinity());  // D is along x
  EXPECT_EQ(set.moving.kind, FeatureKind::kFace);
  // MakeBox's -x side: faces 8 and 9 over the vertices with x bit clear.
  EXPECT_EQ(set.moving.faces, (std::vector<FaceId>{8, 9}));
  EXPECT_EQ(set.moving.vertices, Ids({0, 2, 4, 6}));
}

// Parallel edges pressed together give the depth and both edges as contacts.
// M's lowest edge onto F's highest, both along x: each projects to a point in
// yz, where every edge around them passes through the same point too.
TEST(PaperMethodTest, ParallelEdges) {
  const double quarter = std::numbers::pi / 4;
  // Turned 45 degrees about x, a unit cube's highest edge joins vertices 6
  // and 7 at z = sqrt(2) / 2.
  const auto f =
      MakeBody(TransformMesh(MakeBox(Vector3d::Ones()), At({0, 0, 0}, quarter, {1, 0, 0})));
  const auto m = MakeBody(MakeBox(Vector3d::Constant(0.4)));
  const Isometry3d X_WM =
      At({0.1, 0, std::sqrt(0.5) + 0.2 * std::sqrt(2.0) - kDelta}, quarter, Vector3d::UnitX());
  const ContactSet set = Paper(*m, X_WM, *f, Isometry3d::Identity(), {0, 0, -1});
  EXPECT_NEAR(set.depth_m, kDelta, kDepthTol);
  EXPECT_EQ(set.moving.kind, FeatureKind::kEdge);
  EXPECT_EQ(set.moving.vertices, Ids({0, 1}));
  EXPECT_EQ(set.moving.edges, std::vector<EdgeId>{m->object.FindEdge(0, 1)});
  EXPECT_EQ(set.fixed.kind, FeatureKind::kEdge);
  EXPECT_EQ(set.fixed.vertices, Ids({6, 7}));
  EXPECT_TRUE(std::ranges::count(set.fixed.edges, f->object.FindEdge(6, 7)));
}

// Fig. 6: with F's vertex inside M and no vertex of M inside F, F's vertex decides.
// An octahedron's tip pressed into a box's bottom face: singular case, the
// tip is the fixed contact vertex, and M's side gets the edges its line met.
TEST(PaperMethodTest, Fig6SingularCase) {
  const auto f = MakeBody(MakeOctahedron(0.5));  // tip: vertex 4 at z = 0.5
  const auto m = MakeBody(MakeBox(Vector3d::Constant(0.4)));
  const ContactSet set =
      Paper(*m, At({0.05, -0.03, 0.5 + 0.2 - kDelta}), *f, Isometry3d::Identity(), {0, 0, -1});
  EXPECT_TRUE(set.singular_case);
  EXPECT_NEAR(set.depth_m, kDelta, kDepthTol);
  EXPECT_EQ(set.fixed.kind, FeatureKind::kVertex);
  EXPECT_EQ(set.fixed.vertices, Ids({4}));
  // M's side reports the bottom edges the tip's line crossed, no vertex.
  EXPECT_TRUE(set.moving.vertices.empty());
  EXPECT_EQ(set.moving.kind, FeatureKind::kEdge);
  ASSERT_EQ(set.points.size(), 1u);
  EXPECT_EQ(set.points[0].fixed, (Feature{FeatureKind::kVertex, 4}));
  EXPECT_TRUE(set.points[0].p_WC.isApprox(Vector3d(0, 0, 0.5), 1e-12));
}

// Motion within 1e-9..1e-3 rad of an axis gives the same contact as along it.
// Planes where D projects shorter than 1e-6 are skipped; just above it, the
// plane's t = d / |D_p| is huge and the minimum over planes discards it.
TEST(PaperMethodTest, NearlyAxisAlignedDirection) {
  const auto f = MakeBody(BigBox());
  const auto m = MakeBody(MakeBox(Vector3d::Constant(0.4)));
  for (double tilt : {1e-9, 1e-7, 1e-5, 1e-3}) {
    SCOPED_TRACE(tilt);
    const Vector3d D = Vector3d(tilt, 0.5 * tilt, -1).normalized();
    const ContactSet set =
        Paper(*m, At({0.1, -0.2, kTop + 0.2 - kDelta}), *f, Isometry3d::Identity(), D);
    EXPECT_NEAR(set.depth_m, kDelta / std::abs(D.z()), kDepthTol);
    EXPECT_EQ(set.plane_depths_m[0] == std::numeric_limits<double>::infinity(), tilt < 1e-6);
    EXPECT_EQ(set.moving.faces, (std::vector<FaceId>{0, 1}));
    EXPECT_EQ(set.moving.vertices, Ids({0, 1, 2, 3}));
  }
}

// A direction of length 1e-12 gives the same contact as the unit one.
TEST(PaperMethodTest, TinyDirectionLength) {
  const TorusScene s;
  const ContactSet unit = Paper(*s.m, s.X_WM, *s.f, s.X_WF, s.D_W);
  const ContactSet tiny = Paper(*s.m, s.X_WM, *s.f, s.X_WF, 1e-12 * s.D_W);
  EXPECT_FALSE(tiny.fallback);
  // Normalizing the scaled vector may differ from the unit one in the last
  // bit; that moves the depth by ~1e-16.
  ExpectSameContact(unit, tiny, kDepthTol);
}

// A zero direction falls back to pushing against F's faces and finds the same contact.
// Against F's top faces the estimate is straight down.
TEST(PaperMethodTest, ZeroDirectionUsesFallback) {
  const auto f = MakeBody(BigBox());
  const auto m = MakeBody(MakeBox(Vector3d::Constant(0.4)));
  const ContactSet set =
      Paper(*m, At({0.1, -0.2, kTop + 0.2 - kDelta}), *f, Isometry3d::Identity(), Vector3d::Zero());
  EXPECT_TRUE(set.fallback);
  EXPECT_TRUE(set.direction_W.isApprox(Vector3d(0, 0, -1), 1e-12));
  EXPECT_NEAR(set.depth_m, kDelta, kDepthTol);
  EXPECT_EQ(set.moving.faces, (std::vector<FaceId>{0, 1}));
}

// Depth scales linearly with the scene, from a moving cube 1 nm on a side
// (the smallest object a query takes is 1 nm across) to a 4e6 m floor,
// with the same features.
// Every threshold is relative (the tolerance) or dimensionless (|D_p|).
TEST(PaperMethodTest, ScalesLinearly) {
  for (double scale : {2.5e-9, 1e-4, 1.0, 1e4, 1e6}) {
    SCOPED_TRACE(scale);
    const auto f = MakeBody(MakeBox(scale * Vector3d(4, 4, 1)));
    const auto m = MakeBody(MakeBox(Vector3d::Constant(0.4 * scale)));
    for (const Vector3d& D : {Vector3d(0, 0, -1), Vector3d(0.2, 0.1, -1)}) {
      const ContactSet set = Paper(*m, At(scale * Vector3d(0.1, -0.2, kTop + 0.2 - kDelta)), *f,
                                   Isometry3d::Identity(), D);
      // Relative: the same few roundings as kDepthTol, at every scale.
      EXPECT_NEAR(set.depth_m / scale, kDelta / std::abs(D.normalized().z()), kDepthTol);
      EXPECT_EQ(set.moving.faces, (std::vector<FaceId>{0, 1}));
      EXPECT_EQ(set.moving.vertices, Ids({0, 1, 2, 3}));
    }
  }
}

// Zero-area triangles in the input break nothing.
// The collision layer drops them from the pairs, so through ComputeContact
// the contact is that of the clean scene; forced into the pairs by hand,
// their collinear edges and vertices still give the same depth and M's same
// face contact, and every output stays finite.
TEST(PaperMethodTest, DegenerateTrianglesInTheInput) {
  MeshInput fixed = BigBox();
  const auto first = static_cast<VertexId>(fixed.positions.size());
  // A sliver across F's top under M: three collinear vertices.
  for (double x : {-1.0, 0.0, 1.0}) fixed.positions.emplace_back(x, -0.2, kTop);
  fixed.faces.push_back(FaceInput{{first, first + 1, first + 2}});
  MeshInput moving = MakeBox(Vector3d::Constant(0.4));
  // A sliver along M's vertical edge 0-4, through F's top face.
  moving.positions.push_back((moving.positions[0] + moving.positions[4]) / 2);
  moving.faces.push_back(FaceInput{{0, 8, 4}});
  const auto f = MakeBody(std::move(fixed));
  const auto m = MakeBody(std::move(moving));
  constexpr FaceId kSliver = 12;  // in both: after the box's 12 faces
  const Isometry3d X_FM = At({0.1, -0.2, kTop + 0.2 - kDelta});
  const Vector3d D(0, 0, -1);

  const ContactSet set = Paper(*m, X_FM, *f, Isometry3d::Identity(), D);
  EXPECT_NEAR(set.depth_m, kDelta, kDepthTol);
  EXPECT_EQ(set.moving.faces, (std::vector<FaceId>{0, 1}));
  EXPECT_EQ(set.moving.vertices, Ids({0, 1, 2, 3}));

  const double tol = PairTolerance(*m, *f);
  ContactContext context{m->object, m->model, f->object, f->model, X_FM, D, tol, {}};
  FindIntersectingTriangles(m->model, X_FM, f->model, Isometry3d::Identity(), tol, context.pairs);
  const size_t clean = context.pairs.size();
  for (size_t i = 0; i < clean; ++i) {
    context.pairs.push_back({kSliver, context.pairs[i].b});
    context.pairs.push_back({context.pairs[i].a, kSliver});
  }
  const ContactSetF forced = ReconstructByProjection(context);
  EXPECT_NEAR(forced.depth_m, kDelta, kDepthTol);
  EXPECT_EQ(forced.moving.faces, (std::vector<FaceId>{0, 1}));
  EXPECT_EQ(forced.moving.vertices, Ids({0, 1, 2, 3}));
  for (const ContactPointF& p : forced.points) EXPECT_TRUE(p.p_FC.allFinite());
  EXPECT_TRUE(forced.reversing_vector_F.allFinite());
  for (double t : forced.plane_depths_m) EXPECT_FALSE(std::isnan(t));
}

}  // namespace
}  // namespace hs

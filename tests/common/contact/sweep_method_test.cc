#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <random>

#include "common/collision/triangle_sat.h"
#include "common/contact/contact_query.h"
#include "common/model/procedural.h"
#include "tests/common/contact/contact_test_bodies.h"
#include "tests/common/random_poses.h"

namespace hs {
namespace {

using testing_poses::RandomDirection;
using testing_poses::RandomPose;

using ::testing::ElementsAre;
using testing_bodies::ApexDownPyramid;
using testing_bodies::Body;
using testing_bodies::MakeBody;
using testing_bodies::Translation;

const Vector3d kDown(0, 0, -1);

ContactSet Contact(const Body& moving, const Body& fixed, const Vector3d& direction,
                   double relative_tolerance = 1e-9) {
  absl::StatusOr<ContactSet> set =
      ComputeContact(moving.posed(), fixed.posed(),
                     ContactQuery{.direction_W = direction,
                                  .method = ContactMethod::kSweep3d,
                                  .relative_tolerance = relative_tolerance});
  EXPECT_TRUE(set.ok()) << set.status();
  return set.ok() ? *set : ContactSet{};
}

// A 4 x 4 x 1 slab whose top face is the plane z = 0.
std::unique_ptr<Body> Floor() {
  return MakeBody(MakeBox(Vector3d(4, 4, 1)), Translation(0, 0, -0.5));
}

// Fig. 8 (1): one vertex of a convex object pressed into a face. The apex is
// the only moving contact, the floor's top face the fixed one, and the depth
// is the press depth.
TEST(SweepMethodTest, Fig8VertexOnFace) {
  const double depth = 0.01;
  const auto pyramid = MakeBody(ApexDownPyramid(), Translation(0.3, 0.2, -depth));
  const auto floor = Floor();
  const ContactSet set = Contact(*pyramid, *floor, kDown);
  ASSERT_TRUE(set.colliding);
  EXPECT_TRUE(set.penetrating);
  // Exact up to a few roundings of coordinates of size 1.
  EXPECT_NEAR(set.depth_m, depth, 1e-12);
  EXPECT_TRUE(set.reversing_vector_W.isApprox(Vector3d(0, 0, depth), 1e-9));
  EXPECT_EQ(set.moving.kind, FeatureKind::kVertex);
  EXPECT_THAT(set.moving.vertices, ElementsAre(0));
  EXPECT_EQ(set.fixed.kind, FeatureKind::kFace);
  ASSERT_EQ(set.points.size(), 1u);
  EXPECT_TRUE(set.points[0].p_WC.isApprox(Vector3d(0.3, 0.2, 0), 1e-9));
  EXPECT_EQ(set.points[0].moving, (Feature{FeatureKind::kVertex, 0}));
  EXPECT_EQ(set.points[0].fixed.kind, FeatureKind::kFace);
  EXPECT_TRUE(set.normal_W.isApprox(Vector3d(0, 0, 1), 1e-12));
}

// Fig. 8 (2): an edge on a face. A unit cube turned 45 degrees about x has
// its edge between vertices 0 and 1 lowest; that edge is the contact.
TEST(SweepMethodTest, Fig8EdgeOnFace) {
  const double depth = 0.02;
  Isometry3d X = Translation(0.1, -0.2, std::sqrt(0.5) - depth);
  X.rotate(Eigen::AngleAxisd(M_PI / 4, Vector3d::UnitX()));
  const auto cube = MakeBody(MakeBox(Vector3d(1, 1, 1)), X);
  const auto floor = Floor();
  const ContactSet set = Contact(*cube, *floor, kDown);
  EXPECT_NEAR(set.depth_m, depth, 1e-12);
  EXPECT_EQ(set.moving.kind, FeatureKind::kEdge);
  EXPECT_THAT(set.moving.vertices, ElementsAre(0, 1));
  EXPECT_THAT(set.moving.edges, ElementsAre(cube->object.FindEdge(0, 1)));
  EXPECT_EQ(set.fixed.kind, FeatureKind::kFace);
}

// Fig. 8 (3): a face on a face. The cube's bottom side (faces 0 and 1,
// vertices 0-3) rests in the floor's top side.
TEST(SweepMethodTest, Fig8FaceOnFace) {
  const double depth = 0.005;
  const auto cube = MakeBody(MakeBox(Vector3d(1, 1, 1)), Translation(0.5, 0.5, 0.5 - depth));
  const auto floor = Floor();
  const ContactSet set = Contact(*cube, *floor, kDown);
  EXPECT_NEAR(set.depth_m, depth, 1e-12);
  EXPECT_EQ(set.moving.kind, FeatureKind::kFace);
  EXPECT_THAT(set.moving.faces, ElementsAre(0, 1));
  EXPECT_THAT(set.moving.vertices, ElementsAre(0, 1, 2, 3));
  EXPECT_EQ(set.fixed.kind, FeatureKind::kFace);
  // The floor's top side is faces 2 and 3 of MakeBox.
  EXPECT_THAT(set.fixed.faces, ::testing::IsSubsetOf({2, 3}));
}

// Fig. 8 (4): many points of a non-convex object. A torus lying on the
// floor touches it with its lowest ring of 24 vertices, joined by 24 edges.
TEST(SweepMethodTest, Fig8TorusRingOnFace) {
  const double depth = 0.01;  // < 0.0335, the height of the next ring above the lowest
  const auto torus = MakeBody(MakeTorus(1.0, 0.25, 24, 12), Translation(0.2, 0.1, 0.25 - depth));
  const auto floor = Floor();
  const ContactSet set = Contact(*torus, *floor, kDown);
  EXPECT_NEAR(set.depth_m, depth, 1e-12);
  EXPECT_EQ(set.moving.vertices.size(), 24u);
  EXPECT_EQ(set.moving.edges.size(), 24u);
  EXPECT_EQ(set.moving.kind, FeatureKind::kEdge);
  for (VertexId v : set.moving.vertices) {
    EXPECT_NEAR(torus->object.position(v).z(), -0.25, 1e-12);
  }
}

// The oracle: t* from the sweep intervals of ALL face pairs (no hierarchy),
// chained from t = 0 across gaps below the tolerance as the method does.
double BruteForceDepth(const Body& moving, const Body& fixed, const Vector3d& direction_W,
                       double tolerance) {
  const Isometry3d X_FM = fixed.X_WO.inverse() * moving.X_WO;
  const Vector3d D = (fixed.X_WO.linear().transpose() * direction_W).normalized();
  auto triangle = [](const HapticObject& o, const Isometry3d& X, FaceId f) {
    const auto& v = o.face(f).vertices;
    return Triangle3d{X * o.position(v[0]), X * o.position(v[1]), X * o.position(v[2])};
  };
  std::vector<Interval> intervals;
  for (FaceId a = 0; a < moving.object.num_faces(); ++a) {
    const Triangle3d ta = triangle(moving.object, X_FM, a);
    for (FaceId b = 0; b < fixed.object.num_faces(); ++b) {
      const Interval i =
          SweptIntersection(ta, triangle(fixed.object, Isometry3d::Identity(), b), D, 0.0);
      if (!i.empty()) intervals.push_back(i);
    }
  }
  std::sort(intervals.begin(), intervals.end(),
            [](const Interval& x, const Interval& y) { return x.lo < y.lo; });
  double t = 0;
  for (const Interval& i : intervals) {
    if (i.lo <= t + tolerance && i.hi > t) t = i.hi;
  }
  return t;
}

// All face pairs that intersect with zero margin when M is moved back by t.
int PenetratingPairs(const Body& moving, const Body& fixed, const Vector3d& direction_W, double t) {
  int count = 0;
  Isometry3d X_WM = moving.X_WO;
  X_WM.pretranslate(-t * direction_W.normalized());
  for (FaceId a = 0; a < moving.object.num_faces(); ++a) {
    const auto& va = moving.object.face(a).vertices;
    const Triangle3d ta = {X_WM * moving.object.position(va[0]),
                           X_WM * moving.object.position(va[1]),
                           X_WM * moving.object.position(va[2])};
    for (FaceId b = 0; b < fixed.object.num_faces(); ++b) {
      const auto& vb = fixed.object.face(b).vertices;
      const Triangle3d tb = {fixed.X_WO * fixed.object.position(vb[0]),
                             fixed.X_WO * fixed.object.position(vb[1]),
                             fixed.X_WO * fixed.object.position(vb[2])};
      count += TrianglesIntersect(ta, tb, 0.0);
    }
  }
  return count;
}

// Two non-convex tori, for the tests on random poses.
struct Tori {
  std::unique_ptr<Body> a = MakeBody(MakeTorus(1.0, 0.3, 16, 8));
  std::unique_ptr<Body> b = MakeBody(MakeTorus(0.8, 0.25, 16, 8));

  // Poses both at random near the origin and returns a random direction.
  Vector3d PoseAtRandom(std::mt19937& rng) {
    a->X_WO = RandomPose(rng, 0.4);
    b->X_WO = RandomPose(rng, 0.4);
    return RandomDirection(rng);
  }
};

// On random poses of two non-convex tori, the depth equals the all-pairs
// oracle's; moving back by the reversing vector (plus twice the tolerance)
// separates the objects, and by 0.98 of it does not.
TEST(SweepMethodTest, MatchesAllPairsOracleAndSeparates) {
  Tori tori;
  const auto& a = tori.a;
  const auto& b = tori.b;
  std::mt19937 rng(41);
  int penetrating = 0;
  for (int i = 0; i < 30; ++i) {
    const Vector3d D = tori.PoseAtRandom(rng);
    const ContactSet set = Contact(*a, *b, D);
    if (!set.colliding) {
      EXPECT_EQ(PenetratingPairs(*a, *b, D, 0), 0) << "pose " << i;
      continue;
    }
    EXPECT_NEAR(set.depth_m, BruteForceDepth(*a, *b, D, set.tolerance_m), set.tolerance_m)
        << "pose " << i;
    EXPECT_EQ(PenetratingPairs(*a, *b, D, set.depth_m + 2 * set.tolerance_m), 0) << "pose " << i;
    if (set.penetrating) {
      ++penetrating;
      EXPECT_GT(PenetratingPairs(*a, *b, D, 0.98 * set.depth_m), 0) << "pose " << i;
    }
    EXPECT_FALSE(set.fallback);
  }
  EXPECT_GT(penetrating, 10);
}

// A depth hint (where the objects are expected to be apart) changes where
// the search starts, never the answer: on random poses of two non-convex
// tori the depth is the same to the bit and so are the features, for hints
// short of, at and past the depth; a hint that is not finite, or negative,
// is INVALID_ARGUMENT.
TEST(SweepMethodTest, DepthHintNeverChangesTheAnswer) {
  Tori tori;
  const auto& a = tori.a;
  const auto& b = tori.b;
  std::mt19937 rng(43);
  int compared = 0;
  for (int i = 0; i < 30; ++i) {
    const Vector3d D = tori.PoseAtRandom(rng);
    const ContactSet plain = Contact(*a, *b, D);
    if (!plain.penetrating) continue;
    for (const double scale : {0.5, 1.0, 2.0, 10.0}) {
      absl::StatusOr<ContactSet> hinted =
          ComputeContact(a->posed(), b->posed(),
                         ContactQuery{.direction_W = D, .depth_hint_m = scale * plain.depth_m});
      ASSERT_TRUE(hinted.ok()) << hinted.status();
      EXPECT_EQ(hinted->depth_m, plain.depth_m) << "pose " << i << " hint x" << scale;
      EXPECT_EQ(hinted->moving.vertices, plain.moving.vertices) << "pose " << i;
      EXPECT_EQ(hinted->moving.edges, plain.moving.edges) << "pose " << i;
      EXPECT_EQ(hinted->moving.faces, plain.moving.faces) << "pose " << i;
      EXPECT_EQ(hinted->fixed.vertices, plain.fixed.vertices) << "pose " << i;
      EXPECT_EQ(hinted->fixed.edges, plain.fixed.edges) << "pose " << i;
      EXPECT_EQ(hinted->fixed.faces, plain.fixed.faces) << "pose " << i;
      EXPECT_EQ(hinted->points.size(), plain.points.size()) << "pose " << i;
      // Pairs come in another order: the normal's sum may round apart.
      EXPECT_LT((hinted->normal_W - plain.normal_W).norm(), 1e-12) << "pose " << i;
      ++compared;
    }
  }
  EXPECT_GT(compared, 40);
  for (const double bad :
       {-1e-3, std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN()}) {
    EXPECT_EQ(ComputeContact(a->posed(), b->posed(),
                             ContactQuery{.direction_W = kDown, .depth_hint_m = bad})
                  .status()
                  .code(),
              absl::StatusCode::kInvalidArgument);
  }
}

// Moving the whole scene rigidly (far from the origin, turned) changes
// neither depth nor features, and turns the vectors with it.
TEST(SweepMethodTest, InvariantUnderRigidMotionOfTheScene) {
  Tori tori;
  const auto& a = tori.a;
  const auto& b = tori.b;
  std::mt19937 rng(42);
  for (int i = 0; i < 15; ++i) {
    const Vector3d D = tori.PoseAtRandom(rng);
    const ContactSet here = Contact(*a, *b, D);
    Isometry3d T = Translation(1e5, -2e5, 3e4);
    T.rotate(Eigen::AngleAxisd(1.0, Vector3d(1, 2, 3).normalized()));
    a->X_WO = T * a->X_WO;
    b->X_WO = T * b->X_WO;
    const ContactSet there = Contact(*a, *b, T.linear() * D);
    ASSERT_EQ(here.colliding, there.colliding) << "pose " << i;
    if (!here.colliding) continue;
    // 1e5 offsets cost about 1e5 * 1e-16 = 1e-11 per coordinate.
    EXPECT_NEAR(here.depth_m, there.depth_m, 1e-8) << "pose " << i;
    EXPECT_EQ(here.moving.vertices, there.moving.vertices) << "pose " << i;
    EXPECT_EQ(here.fixed.vertices, there.fixed.vertices) << "pose " << i;
    EXPECT_TRUE((T.linear() * here.reversing_vector_W).isApprox(there.reversing_vector_W, 1e-6))
        << "pose " << i;
  }
}

// A vertex pressed onto the diagonal of the floor's triangulated top quad
// touches a face of the shape, not an edge: the diagonal only splits the
// quad (both triangles share its source polygon).
TEST(SweepMethodTest, DiagonalOfTriangulatedQuadIsFace) {
  // The floor's top quad is split along the line x = y.
  const auto pyramid = MakeBody(ApexDownPyramid(), Translation(0.25, 0.25, -0.01));
  const auto floor = Floor();
  const ContactSet set = Contact(*pyramid, *floor, kDown);
  ASSERT_EQ(set.points.size(), 2u);  // one per triangle of the quad
  for (const ContactPoint& p : set.points) EXPECT_EQ(p.fixed.kind, FeatureKind::kFace);
  EXPECT_EQ(set.fixed.kind, FeatureKind::kFace);
  EXPECT_THAT(set.fixed.faces, ElementsAre(2, 3));
  EXPECT_TRUE(set.fixed.edges.empty());
}

// Touching without penetration: colliding, not penetrating, depth zero.
TEST(SweepMethodTest, TouchingIsNotPenetrating) {
  const auto cube = MakeBody(MakeBox(Vector3d(1, 1, 1)), Translation(0.3, 0.1, 0.5));
  const auto floor = Floor();
  const ContactSet set = Contact(*cube, *floor, kDown);
  EXPECT_TRUE(set.colliding);
  EXPECT_FALSE(set.penetrating);
  EXPECT_EQ(set.depth_m, 0.0);
  EXPECT_EQ(set.moving.kind, FeatureKind::kFace);
  cube->X_WO = Translation(0.3, 0.1, 0.5 + 1e-6);
  EXPECT_FALSE(Contact(*cube, *floor, kDown).colliding);
}

// Parallel edges: a cube turned 45 degrees about x pressed onto another
// such cube turned about y meets it edge across edge (crossing); and laid
// edge along edge (parallel), the contact is still the two edges.
TEST(SweepMethodTest, EdgeOnEdgeCrossingAndParallel) {
  const double depth = 0.01, h = std::sqrt(0.5);
  Isometry3d X_top = Translation(0, 0, 2 * h - depth);
  X_top.rotate(Eigen::AngleAxisd(M_PI / 4, Vector3d::UnitX()));
  Isometry3d X_crossing = Translation(0, 0, 0);
  X_crossing.rotate(Eigen::AngleAxisd(M_PI / 4, Vector3d::UnitY()));
  const auto top = MakeBody(MakeBox(Vector3d(1, 1, 1)), X_top);
  const auto crossing = MakeBody(MakeBox(Vector3d(1, 1, 1)), X_crossing);
  const ContactSet cross = Contact(*top, *crossing, kDown);
  EXPECT_NEAR(cross.depth_m, depth, 1e-12);
  EXPECT_EQ(cross.moving.kind, FeatureKind::kEdge);
  EXPECT_EQ(cross.fixed.kind, FeatureKind::kEdge);
  EXPECT_TRUE(cross.moving.vertices.empty());  // met inside the edge, not at a corner

  Isometry3d X_parallel = Translation(0.2, 0, 0);
  X_parallel.rotate(Eigen::AngleAxisd(-M_PI / 4, Vector3d::UnitX()));
  const auto parallel = MakeBody(MakeBox(Vector3d(1, 1, 1)), X_parallel);
  const ContactSet along = Contact(*top, *parallel, kDown);
  EXPECT_NEAR(along.depth_m, depth, 1e-12);
  EXPECT_EQ(along.moving.kind, FeatureKind::kEdge);
  EXPECT_EQ(along.fixed.kind, FeatureKind::kEdge);
}

// D parallel to the contact face: the cube, sunk 0.01 into the floor, must
// go back sideways by the whole width it overlaps along D.
TEST(SweepMethodTest, DirectionParallelToFace) {
  const auto cube = MakeBody(MakeBox(Vector3d(1, 1, 1)), Translation(1.7, 0, 0.49));
  const auto floor = Floor();  // spans x in [-2, 2]
  const ContactSet set = Contact(*cube, *floor, Vector3d(-1, 0, 0));
  // M spans x in [1.2, 2.2]; moving back along +x it leaves F at x = 2 + 0.5.
  EXPECT_NEAR(set.depth_m, 0.8, 1e-12);
}

// Direction length does not matter down to 1e-12; zero length falls back
// to the direction opposite the touched faces' normals.
TEST(SweepMethodTest, TinyAndZeroDirection) {
  const auto cube = MakeBody(MakeBox(Vector3d(1, 1, 1)), Translation(0.3, 0.1, 0.49));
  const auto floor = Floor();
  const ContactSet unit = Contact(*cube, *floor, kDown);
  const ContactSet tiny = Contact(*cube, *floor, 1e-12 * kDown);
  EXPECT_EQ(unit.depth_m, tiny.depth_m);
  EXPECT_FALSE(tiny.fallback);
  const ContactSet zero = Contact(*cube, *floor, Vector3d::Zero());
  EXPECT_TRUE(zero.fallback);
  EXPECT_TRUE(zero.direction_W.isApprox(kDown, 1e-12));
  EXPECT_NEAR(zero.depth_m, 0.01, 1e-12);
}

// Scaling the whole scene scales the depth linearly, from a pyramid 3 nm
// across (the smallest object a query takes is 1 nm across) to a 4e6 m
// floor.
TEST(SweepMethodTest, ScalesLinearly) {
  for (double s : {1e-9, 1e-4, 1.0, 1e4, 1e6}) {
    SCOPED_TRACE(s);
    const auto pyramid = MakeBody(TransformMesh(ApexDownPyramid(), Isometry3d(Eigen::Scaling(s))),
                                  Translation(0.3 * s, 0.2 * s, -0.01 * s));
    const auto floor = MakeBody(MakeBox(Vector3d(4 * s, 4 * s, s)), Translation(0, 0, -0.5 * s));
    const ContactSet set = Contact(*pyramid, *floor, kDown);
    EXPECT_NEAR(set.depth_m / s, 0.01, 1e-12);
    EXPECT_THAT(set.moving.vertices, ElementsAre(0));
  }
}

}  // namespace
}  // namespace hs

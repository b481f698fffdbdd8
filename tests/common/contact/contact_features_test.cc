#include "common/contact/contact_features.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <set>
#include <vector>

#include "common/collision/triangle_pairs.h"
#include "common/contact/closest_points.h"
#include "common/model/procedural.h"
#include "tests/common/contact/contact_test_bodies.h"
#include "tests/common/contact/expect_same_side.h"

namespace hs {
namespace {

using testing_bodies::Body;
using testing_bodies::MakeBody;
using testing_bodies::Translation;

constexpr double kTolerance = 1e-6;
const Vector3d kDown(0, 0, -1);
const Vector3d kUp(0, 0, 1);

Isometry3d Turn(const Eigen::Quaterniond& q) { return Isometry3d(q); }

Isometry3d TurnAbout(const Vector3d& axis, double angle) {
  return Turn(Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis.normalized())));
}

// A turn that points the box corner (-1, -1, -1) straight down: vertex 0 of
// MakeBox becomes the lowest point.
Isometry3d CornerDown() {
  return Turn(Eigen::Quaterniond::FromTwoVectors(Vector3d(-1, -1, -1), kDown));
}

// A turn that points the box corner (1, 1, 1) straight up: vertex 7 of
// MakeBox becomes the highest point.
Isometry3d CornerUp() { return Turn(Eigen::Quaterniond::FromTwoVectors(Vector3d(1, 1, 1), kUp)); }

// A moving body M, a fixed body F (its frame is F's frame) and M's pose.
struct Touch {
  std::unique_ptr<Body> m, f;
  Isometry3d X_FM;
};

// Locates the contacts of `touch` over every face pair within the
// tolerance, M moving along `direction_F`.
LocatedContacts Locate(const Touch& touch, const Vector3d& direction_F, LocatedContacts out = {},
                       double tolerance = kTolerance) {
  std::vector<TrianglePair> pairs;
  FindIntersectingTriangles(touch.m->model, touch.X_FM, touch.f->model, Isometry3d::Identity(),
                            tolerance, pairs);
  EXPECT_FALSE(pairs.empty()) << "the bodies do not touch";
  const ContactContext context{touch.m->object, touch.m->model, touch.f->object, touch.f->model,
                               touch.X_FM,      direction_F,    tolerance,       pairs};
  LocateContacts(context, touch.X_FM, pairs, out);
  return out;
}

Triangle3d FaceAt(const HapticObject& object, const Isometry3d& X, FaceId f) {
  const auto& v = object.face(f).vertices;
  return {X * object.position(v[0]), X * object.position(v[1]), X * object.position(v[2])};
}

// Brute force: the distance from p to the nearest face of `object` posed at X.
double SurfaceDistance(const Vector3d& p, const HapticObject& object, const Isometry3d& X) {
  double best = std::numeric_limits<double>::infinity();
  for (FaceId f = 0; f < object.num_faces(); ++f) {
    const Triangle3d t = FaceAt(object, X, f);
    best = std::min(best, (ClosestPointOnTriangle(p, t[0], t[1], t[2]) - p).norm());
  }
  return best;
}

// Brute force: the vertices of `object` posed at X within the tolerance of
// `other` posed at X_other.
std::set<VertexId> TouchingVertices(const HapticObject& object, const Isometry3d& X,
                                    const HapticObject& other, const Isometry3d& X_other) {
  std::set<VertexId> touching;
  for (VertexId v = 0; v < object.num_vertices(); ++v) {
    if (SurfaceDistance(X * object.position(v), other, X_other) <= kTolerance) touching.insert(v);
  }
  return touching;
}

// The distance from p to feature `feature` of `object` posed at X.
double FeatureDistance(const Vector3d& p, const HapticObject& object, const Isometry3d& X,
                       const Feature& feature) {
  switch (feature.kind) {
    case FeatureKind::kVertex:
      return (X * object.position(feature.id) - p).norm();
    case FeatureKind::kEdge: {
      const Edge& e = object.edge(feature.id);
      const Vector3d a = X * object.position(e.vertices[0]), b = X * object.position(e.vertices[1]);
      return (ClosestPointOnSegment(p, a, b) - p).norm();
    }
    case FeatureKind::kFace: {
      const Triangle3d t = FaceAt(object, X, feature.id);
      return (ClosestPointOnTriangle(p, t[0], t[1], t[2]) - p).norm();
    }
    default:
      return std::numeric_limits<double>::infinity();
  }
}

// What every located contact must satisfy, whatever the shapes: the vertex
// contacts are exactly the vertices within the tolerance of the other body
// (brute force over all faces), each point lies on the features it names,
// feature pairs do not repeat, and each side lists its contact vertices.
void ExpectConsistent(const Touch& touch, const LocatedContacts& out) {
  const HapticObject &m = touch.m->object, &f = touch.f->object;
  const Isometry3d I = Isometry3d::Identity();
  std::set<VertexId> m_vertices, f_vertices;
  std::set<std::pair<Feature, Feature>> pairs;
  for (const ContactPointF& point : out.points) {
    EXPECT_TRUE(pairs.insert({point.moving, point.fixed}).second) << "a feature pair repeats";
    EXPECT_LE(FeatureDistance(point.p_FC, m, touch.X_FM, point.moving), kTolerance);
    EXPECT_LE(FeatureDistance(point.p_FC, f, I, point.fixed), kTolerance);
    if (point.moving.kind == FeatureKind::kVertex) m_vertices.insert(point.moving.id);
    if (point.fixed.kind == FeatureKind::kVertex) f_vertices.insert(point.fixed.id);
  }
  EXPECT_EQ(m_vertices, TouchingVertices(m, touch.X_FM, f, I));
  EXPECT_EQ(f_vertices, TouchingVertices(f, I, m, touch.X_FM));
  EXPECT_EQ(std::vector<VertexId>(m_vertices.begin(), m_vertices.end()), out.moving.vertices);
  EXPECT_EQ(std::vector<VertexId>(f_vertices.begin(), f_vertices.end()), out.fixed.vertices);
  EXPECT_NEAR(out.normal_F.norm(), 1, 1e-12);
}

// The ids of `object`'s vertices, and of its faces, whose coordinate `axis`
// is (all corners) within 1e-9 of `value`.
std::vector<VertexId> VerticesAt(const HapticObject& object, int axis, double value) {
  std::vector<VertexId> ids;
  for (VertexId v = 0; v < object.num_vertices(); ++v) {
    if (std::abs(object.position(v)[axis] - value) < 1e-9) ids.push_back(v);
  }
  return ids;
}
std::vector<FaceId> FacesAt(const HapticObject& object, int axis, double value) {
  std::vector<FaceId> ids;
  for (FaceId f = 0; f < object.num_faces(); ++f) {
    bool all = true;
    for (VertexId v : object.face(f).vertices)
      all &= std::abs(object.position(v)[axis] - value) < 1e-9;
    if (all) ids.push_back(f);
  }
  return ids;
}

// A unit cube F and a cube M of side 0.4 sitting on its top (z = 0.5),
// off-centre so that no corner of M lies on F's top diagonal.
Touch FaceOnFace() {
  return {MakeBody(MakeBox(Vector3d::Constant(0.4))), MakeBody(MakeBox(Vector3d::Ones())),
          Translation(0.1, 0.03, 0.7)};
}

// M's bottom face on F's top face: both sides are face contacts with M's
// four bottom corners as its contact vertices, and the normal is F's
// outward one.
TEST(ContactFeaturesTest, FaceOnFace) {
  const Touch touch = FaceOnFace();
  const LocatedContacts out = Locate(touch, kDown);
  ExpectConsistent(touch, out);
  EXPECT_EQ(out.moving.kind, FeatureKind::kFace);
  EXPECT_EQ(out.moving.vertices, VerticesAt(touch.m->object, 2, -0.2));
  EXPECT_EQ(out.moving.faces, FacesAt(touch.m->object, 2, -0.2));
  EXPECT_EQ(out.fixed.kind, FeatureKind::kFace);
  EXPECT_TRUE(out.fixed.vertices.empty());
  for (FaceId face : out.fixed.faces) EXPECT_EQ(face / 2, 1) << "not F's top quad (faces 2, 3)";
  EXPECT_TRUE(out.normal_F.isApprox(kUp, 1e-12)) << out.normal_F.transpose();
}

// M turned 45 degrees about x rests on one edge: an edge contact on M (its
// two ends are the contact vertices), a face contact on F.
TEST(ContactFeaturesTest, EdgeOnFace) {
  const double drop = 0.2 * std::sqrt(2.0);
  const Touch touch{MakeBody(MakeBox(Vector3d::Constant(0.4))), MakeBody(MakeBox(Vector3d::Ones())),
                    Translation(0.1, 0.03, 0.5 + drop) * TurnAbout(Vector3d::UnitX(), M_PI / 4)};
  const LocatedContacts out = Locate(touch, kDown);
  ExpectConsistent(touch, out);
  ASSERT_EQ(out.moving.vertices.size(), 2u);
  EXPECT_EQ(out.moving.kind, FeatureKind::kEdge);
  EXPECT_EQ(out.moving.edges, std::vector<EdgeId>{touch.m->object.FindEdge(
                                  out.moving.vertices[0], out.moving.vertices[1])});
  EXPECT_EQ(out.fixed.kind, FeatureKind::kFace);
  EXPECT_TRUE(out.normal_F.isApprox(kUp, 1e-12)) << out.normal_F.transpose();
}

// M's corner on the centre of F's top, which lies on the diagonal that cuts
// F's top square in two: that diagonal is no edge of the box, so F's feature
// is a face, never an edge.
TEST(ContactFeaturesTest, VertexOnAPolygonsDiagonalTouchesTheFace) {
  const Touch touch{MakeBody(MakeBox(Vector3d::Constant(0.4))), MakeBody(MakeBox(Vector3d::Ones())),
                    Translation(0, 0, 0.5 + 0.2 * std::sqrt(3.0)) * CornerDown()};
  const LocatedContacts out = Locate(touch, kDown);
  ExpectConsistent(touch, out);
  ASSERT_FALSE(out.points.empty());
  for (const ContactPointF& point : out.points) {
    EXPECT_EQ(point.moving, (Feature{FeatureKind::kVertex, 0}));
    EXPECT_EQ(point.fixed.kind, FeatureKind::kFace);
    EXPECT_TRUE(point.p_FC.isApprox(Vector3d(0, 0, 0.5), 1e-12));
  }
  EXPECT_EQ(out.moving.kind, FeatureKind::kVertex);
  EXPECT_EQ(out.fixed.kind, FeatureKind::kFace);
  EXPECT_TRUE(out.fixed.edges.empty());
  EXPECT_TRUE(out.normal_F.isApprox(kUp, 1e-12)) << out.normal_F.transpose();
}

// M's corner on F's top rim, an edge between two sides: one contact, on
// that edge, however many faces around it report it.
TEST(ContactFeaturesTest, VertexOnAnEdgeOfTheShape) {
  const Touch touch{MakeBody(MakeBox(Vector3d::Constant(0.4))), MakeBody(MakeBox(Vector3d::Ones())),
                    Translation(0.5, 0.1, 0.5 + 0.2 * std::sqrt(3.0)) * CornerDown()};
  const LocatedContacts out = Locate(touch, kDown);
  ExpectConsistent(touch, out);
  // The rim edge at x = 0.5, z = 0.5 joins F's vertices 5 and 7.
  const Feature rim{FeatureKind::kEdge, touch.f->object.FindEdge(5, 7)};
  ASSERT_EQ(out.points.size(), 1u);
  EXPECT_EQ(out.points[0].moving, (Feature{FeatureKind::kVertex, 0}));
  EXPECT_EQ(out.points[0].fixed, rim);
  EXPECT_EQ(out.fixed.kind, FeatureKind::kEdge);
  EXPECT_EQ(out.fixed.edges, std::vector<EdgeId>{rim.id});
}

// Two boxes each turned to put an edge outward, the edges crossed at right
// angles: one edge-edge contact at the crossing, its normal along the
// edges' cross product, turned against the motion.
TEST(ContactFeaturesTest, CrossedEdges) {
  const double top = 0.5 * std::sqrt(2.0), drop = 0.2 * std::sqrt(2.0);
  const Touch touch{
      MakeBody(MakeBox(Vector3d::Constant(0.4))),
      MakeBody(TransformMesh(MakeBox(Vector3d::Ones()), TurnAbout(Vector3d::UnitY(), M_PI / 4))),
      Translation(0.05, 0.02, top + drop) * TurnAbout(Vector3d::UnitX(), M_PI / 4)};
  const LocatedContacts out = Locate(touch, kDown);
  ExpectConsistent(touch, out);
  ASSERT_EQ(out.points.size(), 1u);
  EXPECT_EQ(out.points[0].moving.kind, FeatureKind::kEdge);
  EXPECT_EQ(out.points[0].fixed.kind, FeatureKind::kEdge);
  EXPECT_TRUE(out.points[0].p_FC.isApprox(Vector3d(0, 0.02, top), 1e-12))
      << out.points[0].p_FC.transpose();
  EXPECT_EQ(out.moving.kind, FeatureKind::kEdge);
  EXPECT_EQ(out.fixed.kind, FeatureKind::kEdge);
  EXPECT_TRUE(out.normal_F.isApprox(kUp, 1e-12)) << out.normal_F.transpose();
}

// F's corner under M's flat bottom: a vertex contact on F, a face contact on
// M, and the normal is M's bottom normal reversed (F toward M).
TEST(ContactFeaturesTest, FixedVertexOnMovingFace) {
  const Touch touch{MakeBody(MakeBox(Vector3d::Constant(0.4))),
                    MakeBody(TransformMesh(MakeBox(Vector3d::Ones()), CornerUp())),
                    Translation(0.05, 0.02, 0.5 * std::sqrt(3.0) + 0.2)};
  const LocatedContacts out = Locate(touch, kDown);
  ExpectConsistent(touch, out);
  ASSERT_FALSE(out.points.empty());
  for (const ContactPointF& point : out.points) {
    EXPECT_EQ(point.fixed, (Feature{FeatureKind::kVertex, 7}));
    EXPECT_EQ(point.moving.kind, FeatureKind::kFace);
  }
  EXPECT_EQ(out.fixed.kind, FeatureKind::kVertex);
  EXPECT_EQ(out.moving.kind, FeatureKind::kFace);
  EXPECT_TRUE(out.normal_F.isApprox(kUp, 1e-12)) << out.normal_F.transpose();
}

// The normal opposes the motion whichever way the query says M moves: M
// moving up out of the contact gets the normal turned down.
TEST(ContactFeaturesTest, NormalOpposesTheMotion) {
  const Touch touch{MakeBody(MakeBox(Vector3d::Constant(0.4))), MakeBody(MakeBox(Vector3d::Ones())),
                    Translation(0.5, 0.1, 0.5 + 0.2 * std::sqrt(3.0)) * CornerDown()};
  const Vector3d slanted = Vector3d(0.3, 0.2, -1).normalized();
  EXPECT_LT(Locate(touch, slanted).normal_F.dot(slanted), 0);
  EXPECT_LT(Locate(touch, -slanted).normal_F.dot(-slanted), 0);
}

// Whether `feature` is edge `e` of `object`, or one of its faces when the
// edge only splits a source polygon (such an edge counts as the face).
bool IsEdgeFeature(const HapticObject& object, EdgeId e, const Feature& feature) {
  if (feature == Feature{FeatureKind::kEdge, e}) return true;
  if (feature.kind != FeatureKind::kFace) return false;
  const auto faces = object.EdgeFaces(e);
  return faces.size() == 2 && object.face(faces[0]).source_polygon != kNoPolygon &&
         object.face(faces[0]).source_polygon == object.face(faces[1]).source_polygon &&
         (feature.id == faces[0] || feature.id == faces[1]);
}

// Brute force over every vertex and every pair of edges at random touching
// poses of a torus on a box (edges of every slant, polygons split by
// diagonals, the box's corners on the torus's small faces): each vertex
// within the tolerance of the other body is a vertex contact, and each pair
// of edges within the tolerance of each other at points more than the
// tolerance from their ends an edge-edge contact, whatever the locator
// rules out early to spare most pairs their closest points.
TEST(ContactFeaturesTest, EveryVertexAndEdgeCrossingIsLocated) {
  constexpr double kWide = 0.01;
  // Hierarchies grown by the tolerance, which is far wider than MakeBody's.
  const auto wide_body = [&](MeshInput mesh) {
    HapticObject object = *HapticObject::Create("body", std::move(mesh));
    CollisionModel model(object, BvType::kObbRss, kWide);
    return std::make_unique<Body>(Body{std::move(object), std::move(model)});
  };
  const std::unique_ptr<Body> m = wide_body(MakeTorus(0.3, 0.1, 12, 8));
  const std::unique_ptr<Body> f = wide_body(MakeBox(Vector3d(1, 0.8, 0.6)));
  std::mt19937 rng(41);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform(-1, 1);
  int poses = 0, crossings = 0, fixed_vertices = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const Eigen::Quaterniond q =
        Eigen::Quaterniond(normal(rng), normal(rng), normal(rng), normal(rng)).normalized();
    const Vector3d jitter(uniform(rng), uniform(rng), uniform(rng));
    Vector3d toward, centre;
    if (trial % 2 == 0) {
      // The centre about a torus' reach (0.4) off the box's surface along a
      // random direction, so that the surfaces touch or cross a little.
      toward = jitter.normalized();
      centre = toward.cwiseProduct(Vector3d(0.5, 0.4, 0.3)) + 0.32 * toward;
    } else {
      // A random point of the torus's surface (a vertex every other time)
      // within a quarter of the tolerance of a corner of the box, for the
      // box's corners on its faces, edges and vertices.
      const Vector3d corner = Vector3d(uniform(rng) < 0 ? -0.5 : 0.5, uniform(rng) < 0 ? -0.4 : 0.4,
                                       uniform(rng) < 0 ? -0.3 : 0.3);
      const FaceId face = static_cast<FaceId>((uniform(rng) + 1) / 2 * m->object.num_faces()) %
                          m->object.num_faces();
      const auto& v = m->object.face(face).vertices;
      const bool at_vertex = trial % 4 == 1;
      const double s = at_vertex ? 0 : (uniform(rng) + 1) / 2;
      const double t = at_vertex ? 0 : (uniform(rng) + 1) / 2 * (1 - s);
      const Vector3d on_surface = m->object.position(v[0]) +
                                  s * (m->object.position(v[1]) - m->object.position(v[0])) +
                                  t * (m->object.position(v[2]) - m->object.position(v[0]));
      centre = corner - q * on_surface + 0.25 * kWide * jitter.normalized();
      toward = corner.normalized();
    }
    const Touch touch{nullptr, nullptr, Translation(centre.x(), centre.y(), centre.z()) * Turn(q)};
    std::vector<TrianglePair> pairs;
    FindIntersectingTriangles(m->model, touch.X_FM, f->model, Isometry3d::Identity(), kWide, pairs);
    if (pairs.empty()) continue;
    ++poses;
    const ContactContext context{m->object,  m->model, f->object, f->model,
                                 touch.X_FM, -toward,  kWide,     pairs};
    LocatedContacts out;
    LocateContacts(context, touch.X_FM, pairs, out);
    const auto vertex_located = [&](int side, VertexId v) {
      return std::any_of(out.points.begin(), out.points.end(), [&](const ContactPointF& point) {
        return (side == 0 ? point.moving : point.fixed) == Feature{FeatureKind::kVertex, v};
      });
    };
    const Isometry3d I = Isometry3d::Identity();
    for (VertexId v = 0; v < m->object.num_vertices(); ++v) {
      if (SurfaceDistance(touch.X_FM * m->object.position(v), f->object, I) <= kWide) {
        EXPECT_TRUE(vertex_located(0, v)) << "trial " << trial << ": vertex " << v << " of M";
      }
    }
    for (VertexId v = 0; v < f->object.num_vertices(); ++v) {
      if (SurfaceDistance(f->object.position(v), m->object, touch.X_FM) <= kWide) {
        ++fixed_vertices;
        EXPECT_TRUE(vertex_located(1, v)) << "trial " << trial << ": vertex " << v << " of F";
      }
    }
    for (EdgeId e1 = 0; e1 < m->object.num_edges(); ++e1) {
      const Edge& a = m->object.edge(e1);
      const Vector3d p1 = touch.X_FM * m->object.position(a.vertices[0]);
      const Vector3d q1 = touch.X_FM * m->object.position(a.vertices[1]);
      for (EdgeId e2 = 0; e2 < f->object.num_edges(); ++e2) {
        const Edge& b = f->object.edge(e2);
        const Vector3d &p2 = f->object.position(b.vertices[0]),
                       &q2 = f->object.position(b.vertices[1]);
        const SegmentClosest c = ClosestPointsOfSegments(p1, q1, p2, q2);
        if ((c.on_first - c.on_second).norm() > kWide) continue;
        if (std::min(c.s, 1 - c.s) * (q1 - p1).norm() <= kWide) continue;
        if (std::min(c.t, 1 - c.t) * (q2 - p2).norm() <= kWide) continue;
        ++crossings;
        EXPECT_TRUE(std::any_of(out.points.begin(), out.points.end(),
                                [&](const ContactPointF& point) {
                                  return IsEdgeFeature(m->object, e1, point.moving) &&
                                         IsEdgeFeature(f->object, e2, point.fixed);
                                }))
            << "trial " << trial << ": edges " << e1 << " and " << e2 << " not located";
      }
    }
  }
  // Enough of both for the test to mean something.
  EXPECT_GT(poses, 300);
  EXPECT_GT(crossings, 1000);
  EXPECT_GT(fixed_vertices, 150);
}

// A second call writes its output over the first's: the same result as into
// a fresh output.
TEST(ContactFeaturesTest, WritesOutputOver) {
  const Touch first = FaceOnFace();
  const Touch second{MakeBody(MakeBox(Vector3d::Constant(0.4))),
                     MakeBody(MakeBox(Vector3d::Ones())),
                     Translation(0.5, 0.1, 0.5 + 0.2 * std::sqrt(3.0)) * CornerDown()};
  const LocatedContacts reused = Locate(second, kDown, Locate(first, kDown));
  const LocatedContacts fresh = Locate(second, kDown);
  ASSERT_EQ(reused.points.size(), fresh.points.size());
  for (size_t i = 0; i < fresh.points.size(); ++i) {
    EXPECT_EQ(reused.points[i].p_FC, fresh.points[i].p_FC);
    EXPECT_EQ(reused.points[i].moving, fresh.points[i].moving);
    EXPECT_EQ(reused.points[i].fixed, fresh.points[i].fixed);
  }

  testing_contacts::ExpectSameSide(reused.moving, fresh.moving);
  testing_contacts::ExpectSameSide(reused.fixed, fresh.fixed);
  EXPECT_EQ(reused.normal_F, fresh.normal_F);
}

}  // namespace
}  // namespace hs

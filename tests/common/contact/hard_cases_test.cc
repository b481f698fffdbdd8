// The hard cases of contact reconstruction, each a named case with an
// analytic oracle, run through the exact 3D method. Every case must give
// finite numbers, the oracle's answer, the same contact kinds and normal
// under perturbations of 1e-9 of the scene's size, and a reversing vector
// that separates the objects.

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <optional>
#include <ostream>
#include <random>
#include <string>

#include "common/contact/contact_query.h"
#include "common/model/procedural.h"
#include "tests/common/contact/contact_test_bodies.h"
#include "tests/common/random_poses.h"

namespace hs {
namespace {

using testing_bodies::ApexDownPyramid;
using testing_bodies::Body;
using testing_bodies::MakeBody;
using testing_bodies::Translation;

// Touching tolerance of these queries, relative to the pair's size: well
// above the 1e-9 perturbations, so that touching stays touching under them.
constexpr double kRelativeTolerance = 1e-7;
constexpr double kPerturbation = 1e-9;

struct HardCase {
  std::string name;
  std::function<MeshInput()> moving_mesh;
  std::function<MeshInput()> fixed_mesh;
  Isometry3d X_WM;
  Isometry3d X_WF = Isometry3d::Identity();
  Vector3d direction = Vector3d(0, 0, -1);
  /// The scene's size: the unit of every tolerance below.
  double scale = 1;
  bool continuous = false;
  // The oracle.
  bool colliding = true;
  double depth = 0;  // along D, in units of `scale`
  /// Up to rounding, but for curved shapes meshed with flat facets.
  double depth_tolerance = 1e-9;
  bool check_kinds = true;
  FeatureKind moving_kind = FeatureKind::kNone;
  FeatureKind fixed_kind = FeatureKind::kNone;
  Vector3d normal = Vector3d(0, 0, 1);
  std::optional<double> time_of_impact = std::nullopt;
};

void PrintTo(const HardCase& c, std::ostream* os) { *os << c.name; }

// A 4 x 4 x 1 slab with its top face at z = 0.
MeshInput Slab() { return TransformMesh(MakeBox(Vector3d(4, 4, 1)), Translation(0, 0, -0.5)); }

// The slab with a sliver along its front top edge: the top is fanned from
// a vertex 1e-12 inside the middle of that edge, so one top triangle is
// 4 long and 1e-12 high, and its neighbours meet at a needle point.
MeshInput SlabWithSliver() {
  MeshInput mesh;
  mesh.materials.emplace_back();
  mesh.positions = {{-2, -2, 0},  {2, -2, 0},  {2, 2, 0},  {-2, 2, 0}, {0, -2 + 1e-12, 0},
                    {-2, -2, -1}, {2, -2, -1}, {2, 2, -1}, {-2, 2, -1}};
  mesh.faces = {// Top: the sliver, then the fan around vertex 4.
                {{0, 1, 4}},
                {{0, 4, 3}},
                {{4, 1, 2}},
                {{4, 2, 3}},
                // Bottom and sides.
                {{5, 8, 7}},
                {{5, 7, 6}},
                {{0, 5, 6}},
                {{0, 6, 1}},
                {{1, 6, 7}},
                {{1, 7, 2}},
                {{2, 7, 8}},
                {{2, 8, 3}},
                {{3, 8, 5}},
                {{3, 5, 0}}};
  return mesh;
}

// A ring of major radius 0.05 m and tube radius 0.008 m in the xy plane.
MeshInput Ring() { return MakeTorus(0.05, 0.008, 64, 16); }

MeshInput UnitCube() { return MakeBox(Vector3d(1, 1, 1)); }

Isometry3d Turned(const Isometry3d& X, double angle, const Vector3d& axis) {
  Isometry3d out = X;
  out.rotate(Eigen::AngleAxisd(angle, axis));
  return out;
}

// Scales a case's geometry and poses by s and moves it by `offset`.
HardCase Rescaled(HardCase c, const std::string& name, double s, const Vector3d& offset) {
  c.name = name;
  const auto scaled = [s](std::function<MeshInput()> mesh) {
    return [s, mesh] { return TransformMesh(mesh(), Isometry3d(Eigen::Scaling(s))); };
  };
  c.moving_mesh = scaled(c.moving_mesh);
  c.fixed_mesh = scaled(c.fixed_mesh);
  for (Isometry3d* X : {&c.X_WM, &c.X_WF}) {
    X->translation() = s * X->translation() + offset;
  }
  c.scale = s;
  return c;
}

std::vector<HardCase> Cases() {
  const double h = std::sqrt(0.5);  // half the diagonal of a unit square
  std::vector<HardCase> cases;
  const HardCase vertex_into_face{.name = "VertexIntoFace",
                                  .moving_mesh = ApexDownPyramid,
                                  .fixed_mesh = Slab,
                                  .X_WM = Translation(0.3, 0.2, -0.01),
                                  .depth = 0.01,
                                  .moving_kind = FeatureKind::kVertex,
                                  .fixed_kind = FeatureKind::kFace};
  cases.push_back(vertex_into_face);
  HardCase on_face = vertex_into_face;
  on_face.name = "VertexExactlyOnFace";
  on_face.X_WM = Translation(0.3, 0.2, 0);
  on_face.depth = 0;
  cases.push_back(on_face);
  cases.push_back(Rescaled(vertex_into_face, "TinyScale", 1e-4, Vector3d::Zero()));
  cases.push_back(Rescaled(vertex_into_face, "HugeScale", 1e4, Vector3d::Zero()));
  cases.push_back(Rescaled(vertex_into_face, "FarFromOrigin", 1, Vector3d(1e5, -1e5, 1e5)));
  HardCase slivers = vertex_into_face;
  slivers.name = "ApexOnSlivers";
  slivers.fixed_mesh = SlabWithSliver;
  slivers.X_WM = Translation(0.5, -1.9999, -0.01);  // 1e-4 from the sliver
  cases.push_back(slivers);

  cases.push_back({.name = "EdgeOnEdgeCrossing",
                   .moving_mesh = UnitCube,
                   .fixed_mesh = UnitCube,
                   .X_WM = Turned(Translation(0, 0, 2 * h - 0.01), M_PI / 4, Vector3d::UnitX()),
                   .X_WF = Turned(Isometry3d::Identity(), M_PI / 4, Vector3d::UnitY()),
                   .depth = 0.01,
                   .moving_kind = FeatureKind::kEdge,
                   .fixed_kind = FeatureKind::kEdge});
  cases.push_back({.name = "EdgeOnEdgeParallel",
                   .moving_mesh = UnitCube,
                   .fixed_mesh = UnitCube,
                   .X_WM = Turned(Translation(0, 0, 2 * h - 0.01), M_PI / 4, Vector3d::UnitX()),
                   .X_WF = Turned(Translation(0.2, 0, 0), -M_PI / 4, Vector3d::UnitX()),
                   .depth = 0.01,
                   .moving_kind = FeatureKind::kEdge,
                   .fixed_kind = FeatureKind::kEdge});
  const HardCase coplanar{.name = "FaceOnFaceCoplanar",
                          .moving_mesh = UnitCube,
                          .fixed_mesh = Slab,
                          .X_WM = Translation(0.3, 0.1, 0.5),
                          .moving_kind = FeatureKind::kFace,
                          .fixed_kind = FeatureKind::kFace};
  cases.push_back(coplanar);
  // Same-size cubes, sides aligned: every face pair meets at an edge of one
  // of the two, so no single pair overlaps deeply, and the rims' side faces
  // must not tilt the normal.
  cases.push_back({.name = "AlignedBoxesPenetrating",
                   .moving_mesh = UnitCube,
                   .fixed_mesh = UnitCube,
                   .X_WM = Translation(0, 0, 0.99),
                   .depth = 0.01,
                   .moving_kind = FeatureKind::kFace,
                   .fixed_kind = FeatureKind::kFace});
  HardCase aligned_touch = cases.back();
  aligned_touch.name = "AlignedBoxesTouching";
  aligned_touch.X_WM = Translation(0, 0, 1);
  aligned_touch.depth = 0;
  cases.push_back(aligned_touch);
  HardCase apart = coplanar;
  apart.name = "FaceBesideFaceCoplanarApart";
  apart.X_WM = Translation(2.6, 0.1, -0.5);  // beside the slab, faces in its planes
  apart.colliding = false;
  apart.moving_kind = apart.fixed_kind = FeatureKind::kNone;
  cases.push_back(apart);
  HardCase grazing = coplanar;
  grazing.name = "GrazingAlongFace";
  grazing.direction = Vector3d(1, 0, 0);  // sliding on the slab: nothing to reverse
  cases.push_back(grazing);
  HardCase sideways{.name = "DirectionParallelToFace",
                    .moving_mesh = UnitCube,
                    .fixed_mesh = Slab,
                    .X_WM = Translation(1.7, 0, 0.49),
                    .direction = Vector3d(-1, 0, 0),
                    // M spans x in [1.2, 2.2]; moving back along +x it leaves at 2.5.
                    .depth = 0.8,
                    .moving_kind = FeatureKind::kFace,
                    .fixed_kind = FeatureKind::kFace,
                    .normal = Vector3d(1, 0, 0)};
  cases.push_back(sideways);
  HardCase tiny_d = vertex_into_face;
  tiny_d.name = "DirectionOfLength1e-12";
  tiny_d.direction *= 1e-12;
  cases.push_back(tiny_d);
  HardCase zero_d = coplanar;
  zero_d.name = "DirectionZero";
  zero_d.X_WM = Translation(0.3, 0.1, 0.49);
  zero_d.direction = Vector3d::Zero();
  zero_d.depth = 0.01;  // pushed back against the touched faces: up
  cases.push_back(zero_d);
  // The hook stands in the xz plane through the ring's hole, centred
  // delta along x: its tube (at x = delta + r) meets the ring's inner side
  // (at x = R - r) when delta = R - 2r, and here it is 4 mm further.
  const double R = 0.05, r = 0.008;
  cases.push_back(
      {.name = "IntertwinedRings",
       .moving_mesh = Ring,
       .fixed_mesh = Ring,
       .X_WM = Turned(Translation(R + R - 2 * r + 0.004, 0, 0), M_PI / 2, Vector3d::UnitX()),
       .direction = Vector3d(1, 0, 0),
       .depth = 0.004,
       // Flat facets lie inside the round tubes by up to
       // r (1 - cos(pi/16)) + R (1 - cos(pi/64)), about 2e-4.
       .depth_tolerance = 5e-4,
       .check_kinds = false,
       .normal = Vector3d(-1, 0, 0)});
  cases.push_back({.name = "ThinPlatePassedThroughInOneStep",
                   .moving_mesh = [] { return MakeBox(Vector3d(0.1, 0.1, 0.1)); },
                   .fixed_mesh = [] { return MakeBox(Vector3d(2, 2, 0.01)); },
                   // The step: 0.2 down from z = 0.1, ending well below the plate.
                   .X_WM = Translation(0, 0, -0.1),
                   .direction = Vector3d(0, 0, -0.2),
                   .continuous = true,
                   // Back to where the cube's bottom (z - 0.05) met the top (0.005).
                   .depth = 0.155,
                   .moving_kind = FeatureKind::kFace,
                   .fixed_kind = FeatureKind::kFace,
                   .time_of_impact = 1 - 0.155 / 0.2});
  return cases;
}

ContactSet Contact(const HardCase& c, const Isometry3d& X_WM) {
  const auto moving = MakeBody(c.moving_mesh(), X_WM);
  const auto fixed = MakeBody(c.fixed_mesh(), c.X_WF);
  const ContactQuery query{.direction_W = c.direction,
                           .method = ContactMethod::kSweep3d,
                           .continuous = c.continuous,
                           .relative_tolerance = kRelativeTolerance};
  const absl::StatusOr<ContactSet> set = ComputeContact(moving->posed(), fixed->posed(), query);
  EXPECT_TRUE(set.ok()) << set.status();
  return set.ok() ? *set : ContactSet{};
}

bool AllFinite(const ContactSet& s) {
  bool finite = std::isfinite(s.depth_m) && s.reversing_vector_W.allFinite() &&
                s.normal_W.allFinite() && s.direction_W.allFinite();
  for (const ContactPoint& p : s.points) finite = finite && p.p_WC.allFinite();
  return finite && (!s.time_of_impact || std::isfinite(*s.time_of_impact));
}

class HardCasesTest : public ::testing::TestWithParam<HardCase> {};

// The case's analytic answer: collision, depth along D, contact kinds on
// both sides, normal, time of impact; and only finite numbers.
TEST_P(HardCasesTest, MatchesOracle) {
  const HardCase& c = GetParam();
  const ContactSet set = Contact(c, c.X_WM);
  EXPECT_TRUE(AllFinite(set));
  ASSERT_EQ(set.colliding, c.colliding);
  if (!c.colliding) return;
  // Depths are exact up to rounding of coordinates of size `scale`.
  EXPECT_NEAR(set.depth_m, c.depth * c.scale, c.depth_tolerance * c.scale);
  EXPECT_EQ(set.penetrating, c.depth > 0);
  if (c.check_kinds) {
    EXPECT_EQ(set.moving.kind, c.moving_kind);
    EXPECT_EQ(set.fixed.kind, c.fixed_kind);
  }
  EXPECT_GT(set.normal_W.dot(c.normal), 1 - 1e-9) << set.normal_W.transpose();
  if (c.time_of_impact) {
    ASSERT_TRUE(set.time_of_impact.has_value());
    EXPECT_NEAR(*set.time_of_impact, *c.time_of_impact, 1e-9);
  }
}

// Moving the object by 1e-9 of the scene's size, or turning it by 1e-9 rad,
// changes neither the contact kinds nor the normal's sense, and the depth
// by no more than the perturbation (fixed seed, 20 perturbations).
TEST_P(HardCasesTest, StableUnderTinyPerturbations) {
  const HardCase& c = GetParam();
  const ContactSet base = Contact(c, c.X_WM);
  std::mt19937 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    SCOPED_TRACE(trial);
    Isometry3d X = c.X_WM;
    X.pretranslate(kPerturbation * c.scale * testing_poses::RandomDirection(rng));
    X.rotate(Eigen::AngleAxisd(kPerturbation, testing_poses::RandomDirection(rng)));
    const ContactSet set = Contact(c, X);
    EXPECT_TRUE(AllFinite(set));
    ASSERT_EQ(set.colliding, base.colliding);
    EXPECT_EQ(set.moving.kind, base.moving.kind);
    EXPECT_EQ(set.fixed.kind, base.fixed.kind);
    if (!base.colliding) continue;
    EXPECT_GT(set.normal_W.dot(base.normal_W), 0.999);
    // The rotation moves points up to 1e-9 x their distance from the
    // object's origin, a few scene sizes at most.
    EXPECT_NEAR(set.depth_m, base.depth_m, 10 * kPerturbation * c.scale);
  }
}

// Moving the object by the reversing vector, and on by twice the touching
// tolerance along -D, leaves the objects apart. Objects that only touch
// have nothing to reverse, and part when moved along the normal.
TEST_P(HardCasesTest, ReversingVectorSeparates) {
  const HardCase& c = GetParam();
  const ContactSet set = Contact(c, c.X_WM);
  if (!set.colliding) {  // apart already: nothing to reverse
    EXPECT_EQ(set.reversing_vector_W, Vector3d::Zero());
    return;
  }
  Isometry3d X = c.X_WM;
  if (set.penetrating) {
    X.pretranslate(set.reversing_vector_W - 2 * set.tolerance_m * set.direction_W);
  } else {
    EXPECT_EQ(set.reversing_vector_W, Vector3d::Zero());
    X.pretranslate(2 * set.tolerance_m * set.normal_W);
  }
  const auto moving = MakeBody(c.moving_mesh(), X);
  const auto fixed = MakeBody(c.fixed_mesh(), c.X_WF);
  EXPECT_FALSE(*AreColliding(moving->posed(), fixed->posed(), kRelativeTolerance));
}

INSTANTIATE_TEST_SUITE_P(All, HardCasesTest, ::testing::ValuesIn(Cases()),
                         [](const ::testing::TestParamInfo<HardCase>& info) {
                           std::string name = info.param.name;
                           std::erase(name, '-');
                           return name;
                         });

}  // namespace
}  // namespace hs

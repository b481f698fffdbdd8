#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <random>

#include "common/contact/contact_context.h"
#include "common/contact/contact_features.h"
#include "common/contact/contact_query.h"
#include "common/model/procedural.h"
#include "tests/common/contact/contact_test_bodies.h"

namespace hs {
namespace {

using testing_bodies::MakeBody;
using testing_bodies::Translation;

// A 0.1 m cube steps from z = 0.5 to z = -0.5 through a 0.01 m plate
// (paper fig. 3 c). A discrete query sees nothing; a continuous one finds
// the first touch at 0.445 of the step (bottom at 0.055 - 0.05 = 0.005, the
// plate's top) and leads the cube back to it, face on face.
TEST(ContinuousContactTest, ThinPlatePassedThroughInOneStep) {
  const auto cube = MakeBody(MakeBox(Vector3d(0.1, 0.1, 0.1)), Translation(0.3, 0.2, -0.5));
  const auto plate = MakeBody(MakeBox(Vector3d(2, 2, 0.01)));
  const Vector3d step(0, 0, -1);
  ContactQuery query{.direction_W = step};
  const ContactSet discrete = *ComputeContact(cube->posed(), plate->posed(), query);
  EXPECT_FALSE(discrete.colliding);
  query.continuous = true;
  const ContactSet set = *ComputeContact(cube->posed(), plate->posed(), query);
  ASSERT_TRUE(set.colliding);
  EXPECT_TRUE(set.penetrating);
  ASSERT_TRUE(set.time_of_impact.has_value());
  // Exact up to roundings of coordinates of size 1.
  EXPECT_NEAR(*set.time_of_impact, 0.445, 1e-12);
  EXPECT_NEAR(set.depth_m, 0.555, 1e-12);
  EXPECT_TRUE(set.reversing_vector_W.isApprox(Vector3d(0, 0, 0.555), 1e-12));
  EXPECT_EQ(set.moving.kind, FeatureKind::kFace);
  EXPECT_THAT(set.moving.faces, ::testing::ElementsAre(0, 1));  // the cube's bottom side
  EXPECT_EQ(set.fixed.kind, FeatureKind::kFace);
}

// When the objects already penetrate at the end of the step, the continuous
// query keeps the discrete depth and adds the time of first touch.
TEST(ContinuousContactTest, PenetratingStepReportsTimeOfImpact) {
  const auto cube =
      MakeBody(MakeBox(Vector3d(0.1, 0.1, 0.1)), Translation(0, 0, 0.05 + 0.005 - 0.02));
  const auto plate = MakeBody(MakeBox(Vector3d(2, 2, 0.01)));
  const ContactQuery discrete{.direction_W = Vector3d(0, 0, -0.1)};
  ContactQuery continuous = discrete;
  continuous.continuous = true;
  const ContactSet a = *ComputeContact(cube->posed(), plate->posed(), discrete);
  const ContactSet b = *ComputeContact(cube->posed(), plate->posed(), continuous);
  EXPECT_NEAR(a.depth_m, 0.02, 1e-12);
  EXPECT_EQ(a.depth_m, b.depth_m);
  EXPECT_FALSE(a.time_of_impact.has_value());
  // It touched after 0.08 of the 0.1 m step.
  EXPECT_NEAR(*b.time_of_impact, 0.8, 1e-12);
}

// FindFirstTouch gives the same first touch without reconstructing the end
// pose: time 0.445 of the step, normal up, the plate's top face, and
// nothing for a step that misses.
TEST(ContinuousContactTest, FirstTouchOfThinPlate) {
  const auto cube = MakeBody(MakeBox(Vector3d(0.1, 0.1, 0.1)), Translation(0.3, 0.2, -0.5));
  const auto plate = MakeBody(MakeBox(Vector3d(2, 2, 0.01)));
  const auto touch = *FindFirstTouch(cube->posed(), plate->posed(), Vector3d(0, 0, -1), 1e-9);
  ASSERT_TRUE(touch.has_value());
  EXPECT_NEAR(touch->time, 0.445, 1e-12);
  EXPECT_TRUE(touch->normal_W.isApprox(Vector3d(0, 0, 1), 1e-12));
  EXPECT_EQ(touch->fixed.kind, FeatureKind::kFace);
  for (const ContactPoint& p : touch->points) EXPECT_NEAR(p.p_WC.z(), 0.005, 1e-12);
  cube->X_WO = Translation(3, 0, -0.5);
  EXPECT_FALSE(
      FindFirstTouch(cube->posed(), plate->posed(), Vector3d(0, 0, -1), 1e-9)->has_value());
}

// The first touch's features are those of a brute force over every face
// pair of the two objects at the touch pose: a 2 cm cube stepping 5 cm
// from random places above a torus, down and tilted (fixed seed).
TEST(ContinuousContactTest, FirstTouchFeaturesMatchBruteForceAtTouch) {
  const auto cube = MakeBody(MakeBox(Vector3d(0.02, 0.02, 0.02)));
  const auto torus = MakeBody(MakeTorus(0.1, 0.04, 48, 24));
  constexpr double kRelativeTolerance = 1e-9;
  const double tolerance = kRelativeTolerance * (cube->object.bounding_box().diagonal().norm() +
                                                 torus->object.bounding_box().diagonal().norm());
  std::mt19937 random(7);
  std::uniform_real_distribution<double> around(-0.15, 0.15), tilt(-0.5, 0.5);
  int touches = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const Vector3d step = Vector3d(tilt(random), tilt(random), -1).normalized() * 0.05;
    const Vector3d end(around(random), around(random), 0.03);
    cube->X_WO = Translation(end.x(), end.y(), end.z());
    const auto touch = *FindFirstTouch(cube->posed(), torus->posed(), step, kRelativeTolerance);
    if (!touch) continue;
    ++touches;
    ContactContext context{cube->object, cube->model,       torus->object, torus->model,
                           cube->X_WO,   step.normalized(), tolerance,     {}};
    context.X_FM.pretranslate(-(1 - touch->time) * step);
    for (FaceId a = 0; a < cube->object.num_faces(); ++a) {
      for (FaceId b = 0; b < torus->object.num_faces(); ++b) {
        if (TrianglesIntersect(context.MovingTriangle(a), context.FixedTriangle(b), tolerance)) {
          context.pairs.push_back({a, b});
        }
      }
    }
    LocatedContacts expected;
    LocateContacts(context, context.X_FM, context.pairs, expected);
    EXPECT_EQ(touch->fixed.kind, expected.fixed.kind) << trial;
    EXPECT_EQ(touch->fixed.vertices, expected.fixed.vertices) << trial;
    EXPECT_EQ(touch->fixed.edges, expected.fixed.edges) << trial;
    EXPECT_EQ(touch->fixed.faces, expected.fixed.faces) << trial;
    ASSERT_EQ(touch->points.size(), expected.points.size()) << trial;
    for (size_t i = 0; i < expected.points.size(); ++i) {
      EXPECT_LT((touch->points[i].p_WC - expected.points[i].p_FC).norm(), 1e-12) << trial;
    }
  }
  // Most steps reach the torus: the test is not vacuous.
  EXPECT_GT(touches, 20);
}

// A step that never reaches the object reports no contact and no time.
TEST(ContinuousContactTest, MissIsNoContact) {
  const auto cube = MakeBody(MakeBox(Vector3d(0.1, 0.1, 0.1)), Translation(3, 0, -0.5));
  const auto plate = MakeBody(MakeBox(Vector3d(2, 2, 0.01)));
  const ContactSet set =
      *ComputeContact(cube->posed(), plate->posed(),
                      ContactQuery{.direction_W = Vector3d(0, 0, -1), .continuous = true});
  EXPECT_FALSE(set.colliding);
  EXPECT_FALSE(set.time_of_impact.has_value());
}

}  // namespace
}  // namespace hs

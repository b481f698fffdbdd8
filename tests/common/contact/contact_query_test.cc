// The doors of common/contact (contact_query.h): what they refuse, and
// that their answers are in the world whatever F's pose.
#include "common/contact/contact_query.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <utility>

#include "common/model/procedural.h"
#include "tests/common/contact/contact_test_bodies.h"

namespace hs {
namespace {

using testing_bodies::MakeBody;
using testing_bodies::Translation;

const Vector3d kDown(0, 0, -1);

// F (a 4 m x 4 m x 1 m floor, top face at its z = 0.5) turned a quarter
// about x and moved: its top faces -y in the world, at y = -0.5 - 2. A
// 1 m cube 1 cm into it along +y. By hand, in the world: direction
// (0, 1, 0), reversing vector (0, -0.01, 0), normal from F toward M
// (0, -1, 0), contact points on the plane y = -2.5 once moved back. In F's
// frame each would read otherwise (the reversing vector (0, 0, 0.01)).
TEST(ContactQueryTest, AnswersAreInTheWorld) {
  Isometry3d X_WF = Translation(0.3, -2, 0.7);
  X_WF.linear() = Eigen::AngleAxisd(M_PI / 2, Vector3d::UnitX()).toRotationMatrix();
  const auto floor = MakeBody(MakeBox(Vector3d(4, 4, 1)), X_WF);
  // The floor's top (its +z) is the world's -y side, at y = -2 - 0.5.
  const auto cube = MakeBody(MakeBox(Vector3d(1, 1, 1)), Translation(0.3, -3.0 + 0.01, 0.7));
  for (const ContactMethod method : {ContactMethod::kSweep3d, ContactMethod::kPaper2d}) {
    const absl::StatusOr<ContactSet> set = ComputeContact(
        cube->posed(), floor->posed(), {.direction_W = Vector3d(0, 1, 0), .method = method});
    ASSERT_TRUE(set.ok()) << set.status();
    ASSERT_TRUE(set->colliding);
    EXPECT_NEAR(set->depth_m, 0.01, 1e-9);
    EXPECT_LT((set->reversing_vector_W - Vector3d(0, -0.01, 0)).norm(), 1e-9);
    EXPECT_LT((set->direction_W - Vector3d(0, 1, 0)).norm(), 1e-12);
    EXPECT_LT((set->normal_W - Vector3d(0, -1, 0)).norm(), 1e-9);
    ASSERT_FALSE(set->points.empty());
    for (const ContactPoint& p : set->points) {
      EXPECT_NEAR(p.p_WC.y(), -2.5, 1e-9);
      EXPECT_LE(std::abs(p.p_WC.x() - 0.3), 0.5 + 1e-9);
    }
  }
}

// Apart: no contact, the query's direction (normalized) and nothing else.
TEST(ContactQueryTest, ApartIsNoContact) {
  const auto floor = MakeBody(MakeBox(Vector3d(4, 4, 1)), Translation(0, 0, -0.5));
  const auto cube = MakeBody(MakeBox(Vector3d(1, 1, 1)), Translation(0, 0, 0.6));
  const ContactSet set = *ComputeContact(cube->posed(), floor->posed(), {.direction_W = 3 * kDown});
  EXPECT_FALSE(set.colliding);
  EXPECT_EQ(set.depth_m, 0);
  EXPECT_EQ(set.direction_W, kDown);
  EXPECT_TRUE(set.points.empty());
  EXPECT_FALSE(*AreColliding(cube->posed(), floor->posed(), 1e-9));
}

// AreColliding: touching within the tolerance counts; a step through a
// 1 mm plate counts with the step and not without it; FindFirstTouch finds
// the touch at the fraction of the step the gap gives (0.1 of 2 m: 0.05).
TEST(ContactQueryTest, CollidingAndFirstTouchByHand) {
  const auto plate = MakeBody(MakeBox(Vector3d(4, 4, 0.001)), Translation(0, 0, -0.0005));
  const auto touching = MakeBody(MakeBox(Vector3d(1, 1, 1)), Translation(0, 0, 0.5));
  EXPECT_TRUE(*AreColliding(touching->posed(), plate->posed(), 1e-9));
  // Started with its bottom 0.1 m over the plate, moved 2 m down: below it.
  const auto through = MakeBody(MakeBox(Vector3d(1, 1, 1)), Translation(0, 0, 0.6 - 2.0));
  const Vector3d step = 2 * kDown;
  EXPECT_FALSE(*AreColliding(through->posed(), plate->posed(), 1e-9));
  EXPECT_TRUE(*AreColliding(through->posed(), plate->posed(), 1e-9, step));
  const std::optional<FirstTouch> touch =
      *FindFirstTouch(through->posed(), plate->posed(), step, 1e-9);
  ASSERT_TRUE(touch.has_value());
  EXPECT_NEAR(touch->time, 0.05, 1e-9);
  EXPECT_LT((touch->normal_W - Vector3d::UnitZ()).norm(), 1e-9);
}

// Bad input is refused before it reaches the collision library: non-finite
// directions, poses or hints, rotations that are not rotations, tolerances
// out of range, models of different bounding volumes.
TEST(ContactQueryTest, RejectsNonFiniteAndNonRigidInput) {
  const auto cube = MakeBody(MakeBox(Vector3d(1, 1, 1)));
  const auto floor = MakeBody(MakeBox(Vector3d(4, 4, 1)), Translation(0, 0, -0.5));
  auto code = [&](const ContactQuery& query) {
    return ComputeContact(cube->posed(), floor->posed(), query).status().code();
  };
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  constexpr auto kInvalid = absl::StatusCode::kInvalidArgument;
  EXPECT_EQ(code({.direction_W = Vector3d(nan, 0, 0)}), kInvalid);
  EXPECT_EQ(code({.direction_W = Vector3d(inf, 0, 0)}), kInvalid);
  EXPECT_EQ(code({.direction_W = kDown, .relative_tolerance = 1e-3}), kInvalid);
  EXPECT_EQ(code({.direction_W = kDown, .relative_tolerance = -1e-9}), kInvalid);
  for (const double hint : {-1e-3, inf, nan}) {
    EXPECT_EQ(code({.direction_W = kDown, .depth_hint_m = hint}), kInvalid) << hint;
  }
  cube->X_WO.linear() *= 2;
  EXPECT_EQ(code({.direction_W = kDown}), kInvalid);
  cube->X_WO = Translation(nan, 0, 0);
  EXPECT_EQ(code({.direction_W = kDown}), kInvalid);
  cube->X_WO = Isometry3d::Identity();
  EXPECT_TRUE(ComputeContact(cube->posed(), floor->posed(), {.direction_W = kDown}).ok());
  const auto aabb_floor =
      MakeBody(MakeBox(Vector3d(4, 4, 1)), Translation(0, 0, -0.5), BvType::kAabb);
  EXPECT_EQ(
      ComputeContact(cube->posed(), aabb_floor->posed(), {.direction_W = kDown}).status().code(),
      kInvalid);
}

// A direction's length does not matter, nor a continuous step's beyond
// where it first touched, up to the largest finite ones: past about 1e154
// their squared length overflows, and the depth came out NaN. By hand: a
// 1 m cube half into a floor, pressed down, backs out 0.5 m; one 10 m
// under a 1 m cube, having come down through it, first touched with its
// centre 1 m above the other's, 11 m back up.
TEST(ContactQueryTest, DirectionsOfAnyFiniteLength) {
  const auto cube = MakeBody(MakeBox(Vector3d(1, 1, 1)));
  const auto floor = MakeBody(MakeBox(Vector3d(4, 4, 1)), Translation(0, 0, -0.5));
  const auto fallen = MakeBody(MakeBox(Vector3d(1, 1, 1)), Translation(0, 0, -10));
  for (const double length : {1e-100, 1.0, 20.0, 1e10, 1e160, 1e300, 1.7e308}) {
    SCOPED_TRACE(length);
    const absl::StatusOr<ContactSet> pressed =
        ComputeContact(cube->posed(), floor->posed(), {.direction_W = length * kDown});
    ASSERT_TRUE(pressed.ok()) << pressed.status();
    EXPECT_DOUBLE_EQ(pressed->depth_m, 0.5);
    EXPECT_TRUE(pressed->reversing_vector_W.isApprox(Vector3d(0, 0, 0.5), 1e-15))
        << pressed->reversing_vector_W.transpose();
    EXPECT_EQ(pressed->direction_W, kDown);
    if (length < 20) continue;  // a step that short never reached the cube
    const absl::StatusOr<ContactSet> through = ComputeContact(
        fallen->posed(), cube->posed(), {.direction_W = length * kDown, .continuous = true});
    ASSERT_TRUE(through.ok()) << through.status();
    EXPECT_TRUE(through->colliding);
    EXPECT_NEAR(through->depth_m, 11, 1e-12);
    EXPECT_TRUE(through->reversing_vector_W.isApprox(Vector3d(0, 0, 11), 1e-12))
        << through->reversing_vector_W.transpose();
    ASSERT_TRUE(through->time_of_impact.has_value());
    EXPECT_NEAR(*through->time_of_impact, 1 - 11 / length, 1e-12);
    const absl::StatusOr<std::optional<FirstTouch>> touch =
        FindFirstTouch(fallen->posed(), cube->posed(), length * kDown, 1e-9);
    ASSERT_TRUE(touch.ok()) << touch.status();
    ASSERT_TRUE(touch->has_value());
    EXPECT_NEAR((*touch)->time, 1 - 11 / length, 1e-12);
    EXPECT_EQ((*touch)->normal_W, -kDown);
    EXPECT_TRUE(AreColliding(fallen->posed(), cube->posed(), 1e-9, length * kDown).value());
  }
}

// An object under kMinObjectSizeM across is refused by each door, either
// side: two cubes 1e-54 m across, half into each other, gave an infinite
// depth and a NaN reversing vector. Cubes at the limit give the depth a
// hand computes (half their side), and so do they at 1e6 m.
TEST(ContactQueryTest, RefusesObjectsUnderANanometreAcross) {
  const auto cube = [](double side, double z) {
    return MakeBody(MakeBox(Vector3d::Constant(side)), Translation(0, 0, z));
  };
  constexpr auto kInvalid = absl::StatusCode::kInvalidArgument;
  for (const double side : {1e-54, 1e-12, 0.99 * kMinObjectSizeM / std::sqrt(3.0)}) {
    SCOPED_TRACE(side);
    const auto speck = cube(side, side / 2);
    const auto other = cube(side, 0);
    const auto unit = cube(1, -0.5);
    EXPECT_EQ(CheckObjectSize(speck->object).code(), kInvalid);
    EXPECT_TRUE(CheckObjectSize(unit->object).ok());
    for (const auto& [m, f] :
         {std::pair{&speck, &other}, std::pair{&speck, &unit}, std::pair{&unit, &speck}}) {
      const absl::StatusOr<ContactSet> set =
          ComputeContact((*m)->posed(), (*f)->posed(), {.direction_W = kDown});
      EXPECT_EQ(set.status().code(), kInvalid);
      EXPECT_NE(set.status().message().find("m a contact query takes"), std::string::npos)
          << set.status().message();
      EXPECT_EQ(AreColliding((*m)->posed(), (*f)->posed(), 1e-9).status().code(), kInvalid);
      EXPECT_EQ(FindFirstTouch((*m)->posed(), (*f)->posed(), kDown, 1e-9).status().code(),
                kInvalid);
    }
  }
  for (const double side : {1.01 * kMinObjectSizeM / std::sqrt(3.0), 1e6}) {
    SCOPED_TRACE(side);
    const auto speck = cube(side, side / 2);
    const auto other = cube(side, 0);
    EXPECT_TRUE(CheckObjectSize(speck->object).ok());
    for (const ContactMethod method : {ContactMethod::kSweep3d, ContactMethod::kPaper2d}) {
      const absl::StatusOr<ContactSet> set =
          ComputeContact(speck->posed(), other->posed(), {.direction_W = kDown, .method = method});
      ASSERT_TRUE(set.ok()) << set.status();
      EXPECT_NEAR(set->depth_m / side, 0.5, 1e-9);
      EXPECT_TRUE(set->reversing_vector_W.allFinite());
    }
  }
}

}  // namespace
}  // namespace hs

// A contact query through a pair cache (ComputeContact's `cache`, kept as a
// scene keeps it) answers bit for bit as the query from scratch: on every
// step of every Table 1 coherent sequence, with both methods, on random
// jumps, and on continuous queries.

#include <gtest/gtest.h>

#include <random>
#include <string>

#include "common/contact/contact_query.h"
#include "tests/common/contact/table1_cases.h"
#include "tests/common/random_poses.h"

namespace hs {
namespace {

using table1::Case;
using table1::GetCase;

// Every field, compared exactly: doubles by value, vectors element by element.
void ExpectIdentical(const ContactSet& cached, const ContactSet& scratch,
                     const std::string& where) {
  SCOPED_TRACE(where);
  EXPECT_EQ(cached.method, scratch.method);
  EXPECT_EQ(cached.colliding, scratch.colliding);
  EXPECT_EQ(cached.penetrating, scratch.penetrating);
  EXPECT_EQ(cached.depth_m, scratch.depth_m);
  EXPECT_EQ(cached.direction_W, scratch.direction_W);
  EXPECT_EQ(cached.reversing_vector_W, scratch.reversing_vector_W);
  EXPECT_EQ(cached.normal_W, scratch.normal_W);
  for (const auto& [c, s] :
       {std::pair{&cached.moving, &scratch.moving}, std::pair{&cached.fixed, &scratch.fixed}}) {
    EXPECT_EQ(c->kind, s->kind);
    EXPECT_EQ(c->vertices, s->vertices);
    EXPECT_EQ(c->edges, s->edges);
    EXPECT_EQ(c->faces, s->faces);
  }
  ASSERT_EQ(cached.points.size(), scratch.points.size());
  for (size_t i = 0; i < cached.points.size(); ++i) {
    EXPECT_EQ(cached.points[i].p_WC, scratch.points[i].p_WC) << "point " << i;
    EXPECT_EQ(cached.points[i].moving, scratch.points[i].moving) << "point " << i;
    EXPECT_EQ(cached.points[i].fixed, scratch.points[i].fixed) << "point " << i;
  }
  EXPECT_EQ(cached.tolerance_m, scratch.tolerance_m);
  EXPECT_EQ(cached.singular_case, scratch.singular_case);
  EXPECT_EQ(cached.fallback, scratch.fallback);
  EXPECT_EQ(cached.time_of_impact, scratch.time_of_impact);
  EXPECT_EQ(cached.plane_depths_m, scratch.plane_depths_m);
}

struct Param {
  int index;
  ContactMethod method;
};

class CoherentContactTest : public testing::TestWithParam<Param> {};

// Every step of the case's coherent sequence (1,000 poses at 1 kHz,
// sliding 0.1 m/s and turning 1 rad/s through the contact).
TEST_P(CoherentContactTest, EveryStepOfTheSequenceIsBitIdentical) {
  const Case& c = GetCase(GetParam().index);
  const ContactQuery query = table1::Query(c, GetParam().method);
  PosedObject moving = c.moving->posed();
  const PosedObject fixed = c.fixed->posed();
  PairCache cache;
  ContactSet cached, scratch;
  int colliding = 0;
  const std::vector<Isometry3d>& poses = table1::CoherentPoses(GetParam().index);
  for (size_t k = 0; k < poses.size(); ++k) {
    moving.X_WO = poses[k];
    ASSERT_TRUE(ComputeContact(moving, fixed, query, cached, &cache).ok());
    ASSERT_TRUE(ComputeContact(moving, fixed, query, scratch).ok());
    ExpectIdentical(cached, scratch, "step " + std::to_string(k));
    if (HasFailure()) return;
    colliding += scratch.colliding;
  }
  EXPECT_EQ(colliding, static_cast<int>(poses.size()));
  // The cache served most queries (two a step with sweep3d).
  EXPECT_GT(cache.hits(), 2 * cache.builds());
}

// Random jumps about the case's pose (up to 5 cm and 0.2 rad), every
// other query back at that pose: regions are built, kept and reused.
TEST_P(CoherentContactTest, RandomJumpsAreBitIdentical) {
  const Case& c = GetCase(GetParam().index);
  const ContactQuery query = table1::Query(c, GetParam().method);
  PosedObject moving = c.moving->posed();
  const PosedObject fixed = c.fixed->posed();
  std::mt19937 rng(41 + GetParam().index);
  std::uniform_real_distribution<double> u(-1, 1);
  PairCache cache;
  ContactSet cached, scratch;
  for (int k = 0; k < 40; ++k) {
    moving.X_WO = c.moving->X_WO;
    if (k % 2 == 0) {
      moving.X_WO.pretranslate(0.05 * Vector3d(u(rng), u(rng), u(rng)));
      moving.X_WO.rotate(Eigen::AngleAxisd(0.2 * u(rng), testing_poses::RandomDirection(rng)));
    }
    ASSERT_TRUE(ComputeContact(moving, fixed, query, cached, &cache).ok());
    ASSERT_TRUE(ComputeContact(moving, fixed, query, scratch).ok());
    ExpectIdentical(cached, scratch, "jump " + std::to_string(k));
    if (HasFailure()) return;
  }
  EXPECT_GT(cache.hits(), 0);
}

// Continuous queries along the sequence, the step's motion as direction.
TEST_P(CoherentContactTest, ContinuousQueriesAreBitIdentical) {
  const Case& c = GetCase(GetParam().index);
  ContactQuery query = table1::Query(c, GetParam().method);
  query.continuous = true;
  PosedObject moving = c.moving->posed();
  const PosedObject fixed = c.fixed->posed();
  PairCache cache;
  ContactSet cached, scratch;
  const std::vector<Isometry3d>& poses = table1::CoherentPoses(GetParam().index);
  for (size_t k = 1; k < poses.size(); k += 25) {
    moving.X_WO = poses[k];
    query.direction_W = poses[k].translation() - poses[k - 1].translation();
    ASSERT_TRUE(ComputeContact(moving, fixed, query, cached, &cache).ok());
    ASSERT_TRUE(ComputeContact(moving, fixed, query, scratch).ok());
    ExpectIdentical(cached, scratch, "step " + std::to_string(k));
    if (HasFailure()) return;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Table1, CoherentContactTest,
    testing::Values(Param{0, ContactMethod::kSweep3d}, Param{1, ContactMethod::kSweep3d},
                    Param{2, ContactMethod::kSweep3d}, Param{3, ContactMethod::kSweep3d},
                    Param{0, ContactMethod::kPaper2d}, Param{1, ContactMethod::kPaper2d},
                    Param{2, ContactMethod::kPaper2d}, Param{3, ContactMethod::kPaper2d}),
    [](const testing::TestParamInfo<Param>& info) {
      return "case" + std::to_string(info.param.index + 1) +
             (info.param.method == ContactMethod::kSweep3d ? "_sweep3d" : "_paper2d");
    });

}  // namespace
}  // namespace hs

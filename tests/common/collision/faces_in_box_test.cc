#include "common/collision/faces_in_box.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <set>
#include <vector>

#include "common/model/procedural.h"
#include "tests/common/random_poses.h"

namespace hs {
namespace {

using testing_poses::RandomPose;

constexpr double kMargin = 0.02;

const BvType kAllTypes[] = {BvType::kObbRss, BvType::kObb, BvType::kRss, BvType::kKios,
                            BvType::kAabb};

// Whether triangle t meets the box, by the separating axis theorem over the
// box's three axes, the triangle's normal and the nine edge crossings: exact
// for two convex sets, and so the brute-force oracle.
bool TriangleMeetsBox(const std::array<Vector3d, 3>& t, const AlignedBox3d& box) {
  const Vector3d half = box.sizes() / 2;
  const std::array<Vector3d, 3> v = {t[0] - box.center(), t[1] - box.center(), t[2] - box.center()};
  const std::array<Vector3d, 3> edges = {v[1] - v[0], v[2] - v[1], v[0] - v[2]};
  std::vector<Vector3d> axes = {Vector3d::UnitX(), Vector3d::UnitY(), Vector3d::UnitZ(),
                                edges[0].cross(edges[1])};
  for (int i = 0; i < 3; ++i) {
    for (const Vector3d& e : edges) axes.push_back(Vector3d::Unit(i).cross(e));
  }
  for (const Vector3d& a : axes) {
    if (a.squaredNorm() == 0) continue;  // parallel: another axis decides
    const double p0 = a.dot(v[0]), p1 = a.dot(v[1]), p2 = a.dot(v[2]);
    const double reach = half.dot(a.cwiseAbs());
    if (std::min({p0, p1, p2}) > reach || std::max({p0, p1, p2}) < -reach) return false;
  }
  return true;
}

std::array<Vector3d, 3> WorldTriangle(const HapticObject& object, FaceId f,
                                      const Isometry3d& X_WO) {
  const auto& v = object.face(f).vertices;
  return {X_WO * object.position(v[0]), X_WO * object.position(v[1]), X_WO * object.position(v[2])};
}

double LongestEdge(const std::array<Vector3d, 3>& t) {
  return std::max({(t[1] - t[0]).norm(), (t[2] - t[1]).norm(), (t[0] - t[2]).norm()});
}

AlignedBox3d Grown(const AlignedBox3d& box, double by) {
  return AlignedBox3d(box.min().array() - by, box.max().array() + by);
}

// Whether face t (world frame) is near enough the box to be found by
// volumes of kind `type`: a leaf's volume reaches at most its longest edge
// and the margin beyond its face (slack, doubled to spare rounding). Volumes
// with an oriented culling box (OBB, OBBRSS) meet the box itself; AABBs meet
// its object-frame bounding box; RSS and kIOS meet FCL's fit to its corners,
// held in a box of half side sqrt(3) half-diagonals about its centre.
bool MayBeFound(BvType type, const std::array<Vector3d, 3>& t_W, const AlignedBox3d& box_W,
                const Isometry3d& X_WO) {
  const double slack = 2 * (LongestEdge(t_W) + kMargin);
  switch (type) {
    case BvType::kObb:
    case BvType::kObbRss:
      return TriangleMeetsBox(t_W, Grown(box_W, slack));
    case BvType::kAabb: {
      const Isometry3d X_OW = X_WO.inverse();
      AlignedBox3d box_O;
      for (int c = 0; c < 8; ++c) box_O.extend(X_OW * box_W.corner(AlignedBox3d::CornerType(c)));
      return TriangleMeetsBox({X_OW * t_W[0], X_OW * t_W[1], X_OW * t_W[2]}, Grown(box_O, slack));
    }
    case BvType::kRss:
    case BvType::kKios: {
      const double reach = std::sqrt(3.0) * box_W.sizes().norm() / 2 + slack;
      return TriangleMeetsBox(
          t_W, AlignedBox3d(box_W.center().array() - reach, box_W.center().array() + reach));
    }
  }
  return false;
}

class FacesInBoxTest : public testing::TestWithParam<BvType> {};

// Against brute force over every face, for random poses and boxes: each face
// within 0.9 margins of the box is found (its grown volume meets the box),
// each face found is near enough (MayBeFound), and none is found twice.
TEST_P(FacesInBoxTest, FindsEveryFaceNearTheBoxAndOnlyThose) {
  const HapticObject torus = *HapticObject::Create("torus", MakeTorus(1.0, 0.3, 48, 24));
  const CollisionModel model(torus, GetParam(), kMargin);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> side(0.01, 0.6);
  int found_total = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const Isometry3d X_WO = RandomPose(rng, 0.5);
    // A box around a random point of the surface, so that most boxes meet it.
    const FaceId seed_face = std::uniform_int_distribution<FaceId>(0, torus.num_faces() - 1)(rng);
    const Vector3d centre = WorldTriangle(torus, seed_face, X_WO)[0];
    const Vector3d half(side(rng), side(rng), side(rng));
    const AlignedBox3d box_W(centre - half, centre + half);
    std::vector<FaceId> found;
    FindFacesInBox(model, X_WO, box_W, found);
    const std::set<FaceId> found_set(found.begin(), found.end());
    ASSERT_EQ(found_set.size(), found.size()) << "a face found twice, trial " << trial;
    found_total += static_cast<int>(found.size());
    // A triangle meeting the box grown by d per axis comes within d*sqrt(3).
    const AlignedBox3d near_box = Grown(box_W, 0.9 * kMargin / std::sqrt(3.0));
    for (FaceId f = 0; f < torus.num_faces(); ++f) {
      const std::array<Vector3d, 3> t = WorldTriangle(torus, f, X_WO);
      if (TriangleMeetsBox(t, near_box)) {
        EXPECT_TRUE(found_set.count(f)) << "face " << f << " missed, trial " << trial;
      }
      if (found_set.count(f)) {
        EXPECT_TRUE(MayBeFound(GetParam(), t, box_W, X_WO))
            << "face " << f << " far from the box, trial " << trial;
      }
    }
  }
  EXPECT_GT(found_total, 0);
}

// A box that holds the whole object (its root volume, and every one below,
// lies inside: an oriented volume's faces are then taken without a test
// each) finds every face once.
TEST_P(FacesInBoxTest, ABoxHoldingTheObjectFindsEveryFaceOnce) {
  const HapticObject torus = *HapticObject::Create("torus", MakeTorus(1.0, 0.3, 48, 24));
  const CollisionModel model(torus, GetParam(), kMargin);
  std::mt19937 rng(12);
  for (int trial = 0; trial < 5; ++trial) {
    const Isometry3d X_WO = RandomPose(rng, 0.5);
    AlignedBox3d box_W;
    for (FaceId f = 0; f < torus.num_faces(); ++f) {
      for (const Vector3d& x : WorldTriangle(torus, f, X_WO)) box_W.extend(x);
    }
    std::vector<FaceId> found;
    FindFacesInBox(model, X_WO, Grown(box_W, 1.0), found);
    std::sort(found.begin(), found.end());
    std::vector<FaceId> every(torus.num_faces());
    std::iota(every.begin(), every.end(), 0);
    EXPECT_EQ(found, every) << "trial " << trial;
  }
}

// Against brute force over every face, for random poses, boxes and planes
// through the surface: a corner in front of the plane (beyond the slack)
// of a face meeting the box is always seen, and a corner is said to be in
// front only when a face that may be found (MayBeFound) has one.
TEST_P(FacesInBoxTest, SeesACornerInFrontOfAPlaneExactlyNearTheBox) {
  const HapticObject torus = *HapticObject::Create("torus", MakeTorus(1.0, 0.3, 48, 24));
  const CollisionModel model(torus, GetParam(), kMargin);
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> side(0.01, 0.6);
  std::normal_distribution<double> gauss(0, 1);
  constexpr double kSlack = 1e-9;
  int in_front = 0, not_in_front = 0;
  // About one plane in nine has nothing in front: 500 trials keep both
  // counts well clear of the floors below whatever the compiler rounds.
  for (int trial = 0; trial < 500; ++trial) {
    const Isometry3d X_WO = RandomPose(rng, 0.5);
    const FaceId seed_face = std::uniform_int_distribution<FaceId>(0, torus.num_faces() - 1)(rng);
    const std::array<Vector3d, 3> seed = WorldTriangle(torus, seed_face, X_WO);
    const Vector3d half(side(rng), side(rng), side(rng));
    const AlignedBox3d box_W(seed[0] - half, seed[0] + half);
    // Through a corner of the face, its normal tilted at random: most such
    // planes have the nearby surface behind them, some not.
    const Vector3d face_n = (seed[1] - seed[0]).cross(seed[2] - seed[0]).normalized();
    const Vector3d n = (face_n + 0.03 * Vector3d(gauss(rng), gauss(rng), gauss(rng))).normalized();
    const bool said = AnyCornerInFront(model, X_WO, box_W, seed[0], n, kSlack);
    bool near_box = false, may_be_found = false;
    for (FaceId f = 0; f < torus.num_faces(); ++f) {
      const std::array<Vector3d, 3> t = WorldTriangle(torus, f, X_WO);
      const bool front = std::any_of(t.begin(), t.end(), [&](const Vector3d& x) {
        return n.dot(x - seed[0]) > kSlack + 1e-12;
      });
      if (!front) continue;
      near_box = near_box || TriangleMeetsBox(t, box_W);
      may_be_found = may_be_found || MayBeFound(GetParam(), t, box_W, X_WO);
    }
    if (near_box) EXPECT_TRUE(said) << "trial " << trial;
    if (said) EXPECT_TRUE(may_be_found) << "trial " << trial;
    ++(said ? in_front : not_in_front);
  }
  EXPECT_GT(in_front, 20);
  EXPECT_GT(not_in_front, 20);
  // Nothing is in front of anything in an empty box.
  EXPECT_FALSE(AnyCornerInFront(model, Isometry3d::Identity(), AlignedBox3d(), Vector3d::Zero(),
                                Vector3d::UnitZ(), kSlack));
}

INSTANTIATE_TEST_SUITE_P(AllBvTypes, FacesInBoxTest, testing::ValuesIn(kAllTypes),
                         [](const testing::TestParamInfo<BvType>& info) {
                           return std::string(BvTypeName(info.param));
                         });

// Faces are appended after what the list held; an empty box adds none, and
// a box far from the object adds none.
TEST(FacesInBoxAppendTest, AppendsAndEmptyOrFarBoxesAddNothing) {
  const HapticObject box = *HapticObject::Create("box", MakeBox(Vector3d::Ones()));
  const CollisionModel model(box, BvType::kObbRss, kMargin);
  std::vector<FaceId> faces = {-7};
  FindFacesInBox(model, Isometry3d::Identity(), AlignedBox3d(), faces);
  EXPECT_EQ(faces, std::vector<FaceId>{-7});
  FindFacesInBox(model, Isometry3d::Identity(),
                 AlignedBox3d(Vector3d::Constant(5), Vector3d::Constant(6)), faces);
  EXPECT_EQ(faces, std::vector<FaceId>{-7});
  // A box holding the whole cube finds all its faces, after the -7.
  FindFacesInBox(model, Isometry3d::Identity(),
                 AlignedBox3d(Vector3d::Constant(-2), Vector3d::Constant(2)), faces);
  ASSERT_EQ(faces.size(), static_cast<size_t>(box.num_faces()) + 1);
  EXPECT_EQ(faces[0], -7);
  std::sort(faces.begin() + 1, faces.end());
  for (FaceId f = 0; f < box.num_faces(); ++f) EXPECT_EQ(faces[f + 1], f);
}

// A zero-area face is never found, even inside the box.
TEST(FacesInBoxAppendTest, DegenerateFacesAreLeftOut) {
  MeshInput mesh = MakeBox(Vector3d::Ones());
  const VertexId first = static_cast<VertexId>(mesh.positions.size());
  mesh.positions.insert(mesh.positions.end(), {{0, 0, 0}, {0.1, 0, 0}, {0.2, 0, 0}});
  mesh.faces.push_back(FaceInput{{first, first + 1, first + 2}, 0, kNoPolygon});
  const HapticObject object = *HapticObject::Create("sliver", std::move(mesh));
  const FaceId sliver = object.num_faces() - 1;
  for (const BvType type : kAllTypes) {
    const CollisionModel model(object, type, kMargin);
    std::vector<FaceId> faces;
    FindFacesInBox(model, Isometry3d::Identity(),
                   AlignedBox3d(Vector3d::Constant(-2), Vector3d::Constant(2)), faces);
    EXPECT_EQ(faces.size(), static_cast<size_t>(object.num_faces()) - 1) << BvTypeName(type);
    EXPECT_EQ(std::count(faces.begin(), faces.end(), sliver), 0) << BvTypeName(type);
  }
}

}  // namespace
}  // namespace hs

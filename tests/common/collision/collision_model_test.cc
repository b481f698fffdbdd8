#include "common/collision/collision_model.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <numeric>
#include <random>
#include <set>
#include <vector>

#include "common/collision/fcl_bvh.h"
#include "common/model/procedural.h"
#include "tests/common/random_poses.h"

namespace hs {
namespace {

using testing_poses::RandomDirection;

constexpr double kMargin = 1e-3;

const BvType kAllTypes[] = {BvType::kObbRss, BvType::kObb, BvType::kRss, BvType::kKios,
                            BvType::kAabb};

HapticObject Torus() { return *HapticObject::Create("torus", MakeTorus(1.0, 0.3, 16, 8)); }

// Whether every node's volume holds every point within 0.9 margins of its
// faces' corners (the corners pushed 0.9 margins along random directions):
// the promise that pairs closer than the margin reach the triangle test. A
// node's faces are leaf_faces[first_primitive, first_primitive + num_primitives).
void ExpectVolumesHoldTheirFacesWithMargin(const CollisionModel& model) {
  const CollisionModel::Impl& impl = model.impl();
  std::mt19937 rng(3);
  std::visit(
      [&](const auto& bvh) {
        for (int n = 0; n < bvh->getNumBVs(); ++n) {
          const auto& node = bvh->getBV(n);
          for (int i = node.first_primitive; i < node.first_primitive + node.num_primitives; ++i) {
            for (const Vector3d& corner : impl.triangle(impl.leaf_faces[i])) {
              for (int k = 0; k < 4; ++k) {
                const Vector3d p = corner + 0.9 * kMargin * RandomDirection(rng);
                ASSERT_TRUE(node.bv.contain(p)) << "node " << n << ", face " << impl.leaf_faces[i];
              }
            }
          }
        }
      },
      impl.bvh);
}

class CollisionModelTest : public testing::TestWithParam<BvType> {};

// Each face is one leaf's, exactly once, and triangle(f) is the object's face f.
TEST_P(CollisionModelTest, LeavesHoldEachFaceOnce) {
  const HapticObject torus = Torus();
  const CollisionModel model(torus, GetParam(), kMargin);
  std::vector<int> faces = model.impl().leaf_faces;
  std::sort(faces.begin(), faces.end());
  std::vector<int> all(torus.num_faces());
  std::iota(all.begin(), all.end(), 0);
  EXPECT_EQ(faces, all);
  for (FaceId f = 0; f < torus.num_faces(); ++f) {
    const auto& v = torus.face(f).vertices;
    const Triangle3d t = model.impl().triangle(f);
    for (int i = 0; i < 3; ++i) EXPECT_EQ(t[i], torus.position(v[i])) << f;
  }
}

// Every volume holds its faces grown by the margin, when built and after a
// refit to moved vertices.
TEST_P(CollisionModelTest, VolumesHoldTheirFacesWithTheMargin) {
  HapticObject torus = Torus();
  CollisionModel model(torus, GetParam(), kMargin);
  ExpectVolumesHoldTheirFacesWithMargin(model);
  // A twist and a squeeze: every vertex moves, the topology stays.
  std::vector<VertexId> ids(torus.num_vertices());
  std::iota(ids.begin(), ids.end(), 0);
  std::vector<Vector3d> moved;
  for (const Vector3d& p : torus.positions()) {
    const Eigen::AngleAxisd twist(0.5 * p.z() + 0.3 * p.x(), Vector3d::UnitZ());
    moved.push_back(twist * Vector3d(p.x(), 0.6 * p.y(), 1.5 * p.z()));
  }
  ASSERT_TRUE(torus.MoveVertices(ids, moved).ok());
  ASSERT_TRUE(model.Sync(torus));
  ExpectVolumesHoldTheirFacesWithMargin(model);
}

// The model reports what it was built with.
TEST_P(CollisionModelTest, ReportsTypeMarginAndVersion) {
  const HapticObject torus = Torus();
  const CollisionModel model(torus, GetParam(), 0.25);
  EXPECT_EQ(model.bv_type(), GetParam());
  EXPECT_EQ(model.margin_m(), 0.25);
  EXPECT_EQ(model.geometry_version(), torus.geometry_version());
}

INSTANTIATE_TEST_SUITE_P(AllBvTypes, CollisionModelTest, testing::ValuesIn(kAllTypes),
                         [](const auto& info) { return std::string(BvTypeName(info.param)); });

// Sync refits only when the object's geometry version moved on, and then
// takes that version; the triangles follow the vertices.
TEST(CollisionModelSyncTest, RefitsOnlyOnANewGeometryVersion) {
  HapticObject box = *HapticObject::Create("box", MakeBox(Vector3d::Ones()));
  CollisionModel model(box, BvType::kObbRss, kMargin);
  EXPECT_FALSE(model.Sync(box));
  const Vector3d far(3, 3, 3);
  ASSERT_TRUE(box.MoveVertices(std::vector<VertexId>{7}, std::vector<Vector3d>{far}).ok());
  EXPECT_TRUE(model.Sync(box));
  EXPECT_EQ(model.geometry_version(), box.geometry_version());
  EXPECT_FALSE(model.Sync(box));
  const FaceId f = box.VertexFaces(7)[0];
  const auto& v = box.face(f).vertices;
  const Triangle3d t = model.impl().triangle(f);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(t[i], box.position(v[i]));
}

// centre is the box's centre, radius the farthest vertex from it, and each
// face's reach its farthest corner: checked by brute force, and again after
// a vertex moves.
TEST(CollisionModelSyncTest, CentreRadiusAndReachBoundTheVertices) {
  HapticObject sphere = *HapticObject::Create("sphere", MakeIcosphere(0.5, 2));
  CollisionModel model(sphere, BvType::kObbRss, kMargin);
  auto expect_bounds = [&] {
    const CollisionModel::Impl& impl = model.impl();
    EXPECT_TRUE(impl.centre.isApprox(sphere.bounding_box().center()));
    double radius = 0;
    for (const Vector3d& p : sphere.positions())
      radius = std::max(radius, (p - impl.centre).norm());
    EXPECT_DOUBLE_EQ(impl.radius, radius);
    for (FaceId f = 0; f < sphere.num_faces(); ++f) {
      double reach = 0;
      for (VertexId v : sphere.face(f).vertices) {
        reach = std::max(reach, (sphere.position(v) - impl.centre).norm());
      }
      EXPECT_DOUBLE_EQ(impl.face_reach[f], reach) << f;
      EXPECT_LE(impl.face_reach[f], impl.radius);
    }
  };
  expect_bounds();
  ASSERT_TRUE(
      sphere.MoveVertices(std::vector<VertexId>{0}, std::vector<Vector3d>{Vector3d(2, 0, 0)}).ok());
  ASSERT_TRUE(model.Sync(sphere));
  expect_bounds();
}

// A zero-area face is marked degenerate and its leaf-order box is empty (the
// leaf test never meets it); the others are not, and their boxes hold them.
TEST(CollisionModelSyncTest, DegenerateFacesAreMarkedAndNeverMet) {
  MeshInput mesh = MakeBox(Vector3d::Ones());
  // A sliver: three points on one line.
  const VertexId first = static_cast<VertexId>(mesh.positions.size());
  mesh.positions.insert(mesh.positions.end(), {{2, 0, 0}, {3, 0, 0}, {4, 0, 0}});
  mesh.faces.push_back(FaceInput{{first, first + 1, first + 2}, 0, kNoPolygon});
  const HapticObject object = *HapticObject::Create("sliver", std::move(mesh));
  const CollisionModel model(object, BvType::kObbRss, kMargin);
  const CollisionModel::Impl& impl = model.impl();
  const FaceId sliver = object.num_faces() - 1;
  for (FaceId f = 0; f < object.num_faces(); ++f)
    EXPECT_EQ(impl.degenerate[f] != 0, f == sliver) << f;
  for (size_t i = 0; i < impl.leaf_faces.size(); ++i) {
    for (int d = 0; d < 3; ++d) {
      if (impl.leaf_faces[i] == sliver) {
        EXPECT_GT(impl.leaf_order_lo[d][i], impl.leaf_order_hi[d][i]);
        continue;
      }
      for (const Vector3d& corner : impl.triangle(impl.leaf_faces[i])) {
        EXPECT_LE(impl.leaf_order_lo[d][i], corner[d]);
        EXPECT_GE(impl.leaf_order_hi[d][i], corner[d]);
      }
    }
  }
  // Then the empty boxes a scan in lanes may read past the last face.
  for (int d = 0; d < 3; ++d) {
    ASSERT_EQ(impl.leaf_order_lo[d].size(), impl.leaf_faces.size() + BoxColumns::kReadPast);
    ASSERT_EQ(impl.leaf_order_hi[d].size(), impl.leaf_order_lo[d].size());
    for (size_t i = impl.leaf_faces.size(); i < impl.leaf_order_lo[d].size(); ++i) {
      EXPECT_GT(impl.leaf_order_lo[d][i], impl.leaf_order_hi[d][i]) << i;
    }
  }
}

// Each node's face box is exactly the least and greatest coordinates of
// its faces' leaf-order boxes (brute force over the node's faces), for
// every kind of volume, on a mesh with a degenerate face (whose empty box
// adds nothing), and again after a vertex moves.
void ExpectNodeFaceBoxesHoldExactlyTheirFaces(const CollisionModel& model) {
  const CollisionModel::Impl& impl = model.impl();
  std::visit(
      [&](const auto& bvh) {
        ASSERT_EQ(impl.node_face_box.size(), static_cast<size_t>(bvh->getNumBVs()));
        for (int n = 0; n < bvh->getNumBVs(); ++n) {
          const auto& node = bvh->getBV(n);
          for (int d = 0; d < 3; ++d) {
            double lo = std::numeric_limits<double>::infinity(), hi = -lo;
            for (int i = node.first_primitive; i < node.first_primitive + node.num_primitives;
                 ++i) {
              lo = std::min(lo, impl.leaf_order_lo[d][i]);
              hi = std::max(hi, impl.leaf_order_hi[d][i]);
            }
            EXPECT_EQ(impl.node_face_box[n].lo[d], lo) << "node " << n << ", axis " << d;
            EXPECT_EQ(impl.node_face_box[n].hi[d], hi) << "node " << n << ", axis " << d;
          }
        }
      },
      impl.bvh);
}

TEST_P(CollisionModelTest, NodeFaceBoxesHoldExactlyTheirFaces) {
  MeshInput mesh = MakeTorus(1.0, 0.3, 16, 8);
  const VertexId first = static_cast<VertexId>(mesh.positions.size());
  mesh.positions.insert(mesh.positions.end(), {{2, 0, 0}, {3, 0, 0}, {4, 0, 0}});
  mesh.faces.push_back(FaceInput{{first, first + 1, first + 2}, 0, kNoPolygon});
  HapticObject object = *HapticObject::Create("torus and sliver", std::move(mesh));
  CollisionModel model(object, GetParam(), kMargin);
  ExpectNodeFaceBoxesHoldExactlyTheirFaces(model);
  ASSERT_TRUE(
      object.MoveVertices(std::vector<VertexId>{0}, std::vector<Vector3d>{Vector3d(2, 1, 0.5)})
          .ok());
  ASSERT_TRUE(model.Sync(object));
  ExpectNodeFaceBoxesHoldExactlyTheirFaces(model);
  // The root reaches the moved vertex, not the sliver's far end (x = 4).
  EXPECT_EQ(model.impl().node_face_box[0].hi[0], 2);
}

// Every model gets an id of its own, kept when it is moved.
TEST(CollisionModelSyncTest, IdsAreUniqueAndSurviveMoves) {
  const HapticObject box = *HapticObject::Create("box", MakeBox(Vector3d::Ones()));
  std::set<uint64_t> ids;
  std::vector<CollisionModel> models;
  for (int i = 0; i < 5; ++i) {
    models.emplace_back(box, BvType::kAabb, 0);
    EXPECT_TRUE(ids.insert(models.back().impl().id).second);
  }
  const uint64_t id = models[0].impl().id;
  CollisionModel moved = std::move(models[0]);
  EXPECT_EQ(moved.impl().id, id);
}

}  // namespace
}  // namespace hs

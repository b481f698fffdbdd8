#include "common/contact/placed_vertices.h"

#include <gtest/gtest.h>

#include <random>

#include "common/model/procedural.h"
#include "tests/common/random_poses.h"

namespace hs {
namespace {

// Against placing each corner directly (as ContactContext::MovingTriangle
// does): every face of a torus, asked for twice, in a random order, at
// random poses, bit for bit; after a Reset to another pose, the new pose's
// corners, never the last one's.
TEST(PlacedVerticesTest, FacesAreTheirCornersPlacedDirectly) {
  absl::StatusOr<HapticObject> torus = HapticObject::Create("torus", MakeTorus(0.1, 0.03, 24, 12));
  ASSERT_TRUE(torus.ok());
  std::mt19937 rng(11);
  PlacedVertices placed;
  for (int round = 0; round < 4; ++round) {
    const Isometry3d X = testing_poses::RandomPose(rng, 0.5);
    placed.Reset(*torus, X);
    for (int pass = 0; pass < 2; ++pass) {
      for (int k = 0; k < torus->num_faces(); ++k) {
        const FaceId f = std::uniform_int_distribution<int>(0, torus->num_faces() - 1)(rng);
        const auto& v = torus->face(f).vertices;
        const Triangle3d face = placed.Face(f);
        for (int i = 0; i < 3; ++i) {
          EXPECT_EQ(face[i], Vector3d(X * torus->position(v[i]))) << "face " << f;
        }
      }
    }
  }
}

}  // namespace
}  // namespace hs

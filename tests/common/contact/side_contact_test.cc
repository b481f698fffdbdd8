#include "common/contact/side_contact.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "common/model/procedural.h"
#include "tests/common/contact/expect_same_side.h"

namespace hs {
namespace {

// The oracle, by brute force over every edge and face: those whose ends (or
// corners) are all contact vertices, with the touched ones, sorted.
SideContact BruteForce(const HapticObject& object, std::vector<VertexId> vertices,
                       std::vector<EdgeId> touched_edges, std::vector<FaceId> touched_faces) {
  auto is_contact = [&](VertexId v) {
    return std::find(vertices.begin(), vertices.end(), v) != vertices.end();
  };
  SideContact side;
  std::sort(vertices.begin(), vertices.end());
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  side.vertices = vertices;
  for (EdgeId e = 0; e < object.num_edges(); ++e) {
    const bool touched =
        std::find(touched_edges.begin(), touched_edges.end(), e) != touched_edges.end();
    if (touched ||
        (is_contact(object.edge(e).vertices[0]) && is_contact(object.edge(e).vertices[1]))) {
      side.edges.push_back(e);
    }
  }
  for (FaceId f = 0; f < object.num_faces(); ++f) {
    const auto& c = object.face(f).vertices;
    const bool touched =
        std::find(touched_faces.begin(), touched_faces.end(), f) != touched_faces.end();
    if (touched || (is_contact(c[0]) && is_contact(c[1]) && is_contact(c[2]))) {
      side.faces.push_back(f);
    }
  }
  side.kind = !side.faces.empty()      ? FeatureKind::kFace
              : !side.edges.empty()    ? FeatureKind::kEdge
              : !side.vertices.empty() ? FeatureKind::kVertex
                                       : FeatureKind::kNone;
  return side;
}

// On a box: two ends of one edge make an edge contact, the four corners of
// a side a face contact (its two triangles, its rim and its diagonal), and
// two opposite corners stay a vertex contact.
TEST(SideContactTest, BoxCornersMakeEdgesAndFaces) {
  const HapticObject box = *HapticObject::Create("box", MakeBox(Vector3d::Ones()));
  SideContact side;
  AggregateSide(box, std::vector<VertexId>{1, 0}, {}, {}, side);
  EXPECT_EQ(side.kind, FeatureKind::kEdge);
  EXPECT_EQ(side.vertices, (std::vector<VertexId>{0, 1}));
  EXPECT_EQ(side.edges, std::vector<EdgeId>{box.FindEdge(0, 1)});
  EXPECT_TRUE(side.faces.empty());

  // Vertices 0..3 are the -z side, faces 0 and 1 (MakeBox's order).
  AggregateSide(box, std::vector<VertexId>{3, 2, 1, 0}, {}, {}, side);
  EXPECT_EQ(side.kind, FeatureKind::kFace);
  EXPECT_EQ(side.faces, (std::vector<FaceId>{0, 1}));
  EXPECT_EQ(side.edges.size(), 5u);  // four rim edges and the diagonal

  AggregateSide(box, std::vector<VertexId>{0, 7}, {}, {}, side);
  EXPECT_EQ(side.kind, FeatureKind::kVertex);
  EXPECT_TRUE(side.edges.empty());
  EXPECT_TRUE(side.faces.empty());

  AggregateSide(box, {}, {}, {}, side);
  EXPECT_EQ(side.kind, FeatureKind::kNone);
  EXPECT_TRUE(side.vertices.empty());
}

// Edges and faces touched inside count without any contact vertex, and
// repeated ids come out once.
TEST(SideContactTest, TouchedFeaturesCountAndRepeatsGo) {
  const HapticObject box = *HapticObject::Create("box", MakeBox(Vector3d::Ones()));
  SideContact side;
  AggregateSide(box, {}, std::vector<EdgeId>{4, 2, 4}, {}, side);
  EXPECT_EQ(side.kind, FeatureKind::kEdge);
  EXPECT_EQ(side.edges, (std::vector<EdgeId>{2, 4}));
  AggregateSide(box, std::vector<VertexId>{5, 5}, {}, std::vector<FaceId>{7, 3, 7}, side);
  EXPECT_EQ(side.kind, FeatureKind::kFace);
  EXPECT_EQ(side.vertices, std::vector<VertexId>{5});
  EXPECT_EQ(side.faces, (std::vector<FaceId>{3, 7}));
}

// On an icosphere, random sets of contact vertices, touched edges and faces
// (with repeats) give what the all-edges, all-faces oracle gives, each call
// written over the last one's output.
TEST(SideContactTest, MatchesBruteForceOnRandomSets) {
  const HapticObject sphere = *HapticObject::Create("sphere", MakeIcosphere(1, 2));
  std::mt19937 rng(5);
  std::uniform_int_distribution<VertexId> vertex(0, sphere.num_vertices() - 1);
  std::uniform_int_distribution<EdgeId> edge(0, sphere.num_edges() - 1);
  std::uniform_int_distribution<FaceId> face(0, sphere.num_faces() - 1);
  std::uniform_int_distribution<int> count(0, 40);
  SideContact side;
  for (int k = 0; k < 200; ++k) {
    std::vector<VertexId> vertices;
    std::vector<EdgeId> edges;
    std::vector<FaceId> faces;
    // Neighbourhoods of one vertex, so that edges and faces fill in.
    const VertexId centre = vertex(rng);
    for (EdgeId e : sphere.VertexEdges(centre)) {
      if (rng() % 3) vertices.push_back(sphere.edge(e).vertices[rng() % 2]);
    }
    for (int i = count(rng); i > 0; --i) vertices.push_back(vertex(rng));
    for (int i = count(rng) / 8; i > 0; --i) edges.push_back(edge(rng));
    for (int i = count(rng) / 8; i > 0; --i) faces.push_back(face(rng));
    AggregateSide(sphere, vertices, edges, faces, side);
    SCOPED_TRACE(k);
    testing_contacts::ExpectSameSide(side, BruteForce(sphere, vertices, edges, faces));
  }
}

}  // namespace
}  // namespace hs

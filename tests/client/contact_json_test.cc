#include "client/contact_json.h"

#include <gtest/gtest.h>

#include <limits>

namespace hs::cli {
namespace {

// Every field is there under its name: vectors as arrays, kinds by name,
// an unset time of impact and infinite plane depths as null.
TEST(ContactJsonTest, EveryFieldByName) {
  ContactSet set;
  set.method = ContactMethod::kPaper2d;
  set.colliding = true;
  set.penetrating = true;
  set.depth_m = 0.002;
  set.direction_W = Vector3d(0, 0, -1);
  set.reversing_vector_W = Vector3d(0, 0, 0.002);
  set.normal_W = Vector3d(0, 0, 1);
  set.tolerance_m = 1e-6;
  set.moving = {.kind = FeatureKind::kFace, .vertices = {0, 1, 2}, .edges = {4}, .faces = {7}};
  set.fixed.kind = FeatureKind::kVertex;
  set.fixed.vertices = {5};
  set.points.push_back({Vector3d(1, 2, 3), {FeatureKind::kVertex, 0}, {FeatureKind::kFace, 9}});
  set.plane_depths_m = {0.002, std::numeric_limits<double>::infinity(), 0.003};
  const nlohmann::ordered_json j = ContactSetToJson(set);
  EXPECT_EQ(j["method"], "paper");
  EXPECT_EQ(j["colliding"], true);
  EXPECT_EQ(j["penetrating"], true);
  EXPECT_EQ(j["depth_m"], 0.002);
  EXPECT_EQ(j["direction_W"], nlohmann::ordered_json({0.0, 0.0, -1.0}));
  EXPECT_EQ(j["reversing_vector_W_m"], nlohmann::ordered_json({0.0, 0.0, 0.002}));
  EXPECT_EQ(j["normal_W"], nlohmann::ordered_json({0.0, 0.0, 1.0}));
  EXPECT_EQ(j["tolerance_m"], 1e-6);
  EXPECT_EQ(j["singular_case"], false);
  EXPECT_EQ(j["fallback"], false);
  EXPECT_TRUE(j["time_of_impact"].is_null());
  EXPECT_EQ(j["plane_depths_m"].dump(), "[0.002,null,0.003]");
  EXPECT_EQ(j["moving"].dump(), R"({"kind":"face","vertices":[0,1,2],"edges":[4],"faces":[7]})");
  EXPECT_EQ(j["fixed"]["kind"], "vertex");
  ASSERT_EQ(j["points"].size(), 1u);
  EXPECT_EQ(j["points"][0].dump(), R"({"p_WC_m":[1.0,2.0,3.0],"moving":{"kind":"vertex","id":0},)"
                                   R"("fixed":{"kind":"face","id":9}})");
  set.method = ContactMethod::kSweep3d;
  set.time_of_impact = 0.25;
  const nlohmann::ordered_json k = ContactSetToJson(set);
  EXPECT_EQ(k["method"], "3d");
  EXPECT_EQ(k["time_of_impact"], 0.25);
}

// Each kind has its name; none is "none".
TEST(ContactJsonTest, KindNames) {
  EXPECT_STREQ(FeatureKindName(FeatureKind::kVertex), "vertex");
  EXPECT_STREQ(FeatureKindName(FeatureKind::kEdge), "edge");
  EXPECT_STREQ(FeatureKindName(FeatureKind::kFace), "face");
  EXPECT_STREQ(FeatureKindName(FeatureKind::kNone), "none");
}

}  // namespace
}  // namespace hs::cli

#include "client/pose_args.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

namespace hs::cli {
namespace {

// Exactly the numbers asked for, in order; signs, exponents and spaces
// around them as absl reads them.
TEST(PoseArgsTest, NumbersAndVectors) {
  const absl::StatusOr<std::vector<double>> numbers = ParseNumbers("1,-2.5,3e-3, 4", 4);
  ASSERT_TRUE(numbers.ok()) << numbers.status();
  EXPECT_EQ(*numbers, (std::vector<double>{1, -2.5, 3e-3, 4}));
  const absl::StatusOr<Vector3d> v = ParseVector3("0.1,0.2,-0.3");
  ASSERT_TRUE(v.ok());
  EXPECT_EQ(*v, Vector3d(0.1, 0.2, -0.3));
}

// A wrong count, an empty or non-numeric part, or a number that is not
// finite is INVALID_ARGUMENT quoting the text.
TEST(PoseArgsTest, BadNumbersAreRefused) {
  for (const char* text : {"1,2", "1,2,3,4", "", "1,,3", "1,x,3", "1,nan,3", "1,inf,3", "1;2;3"}) {
    const absl::StatusOr<Vector3d> v = ParseVector3(text);
    EXPECT_EQ(v.status().code(), absl::StatusCode::kInvalidArgument) << text;
    EXPECT_NE(v.status().message().find("'"), std::string::npos) << v.status();
  }
}

// A pose is the translation, then the rotation vector: a quarter turn about
// z turns x into y; a zero vector is no rotation.
TEST(PoseArgsTest, PosesTranslateThenTurnByTheRotationVector) {
  const absl::StatusOr<Isometry3d> X =
      ParsePose("1,2,3,0,0," + std::to_string(std::numbers::pi / 2));
  ASSERT_TRUE(X.ok()) << X.status();
  EXPECT_TRUE(X->translation().isApprox(Vector3d(1, 2, 3)));
  EXPECT_TRUE((X->linear() * Vector3d::UnitX()).isApprox(Vector3d::UnitY(), 1e-6));
  const absl::StatusOr<Isometry3d> still = ParsePose("0,0,0,0,0,0");
  ASSERT_TRUE(still.ok());
  EXPECT_TRUE(still->linear().isIdentity());
  EXPECT_EQ(ParsePose("1,2,3").status().code(), absl::StatusCode::kInvalidArgument);
  // The rotation vector's length is the angle, its direction the axis.
  const Vector3d axis = Vector3d(1, -2, 0.5).normalized();
  const Isometry3d Y = PoseFromNumbers(Vector3d::Zero(), 0.7 * axis);
  const Eigen::AngleAxisd turn(Y.linear());
  EXPECT_NEAR(turn.angle(), 0.7, 1e-12);
  EXPECT_TRUE(turn.axis().isApprox(axis, 1e-12));
}

// "ID:x,y,z" gives the id and the position; anything else is refused.
TEST(PoseArgsTest, VertexMoves) {
  const absl::StatusOr<std::pair<int, Vector3d>> move = ParseVertexMove("17:0.1,0,-2");
  ASSERT_TRUE(move.ok()) << move.status();
  EXPECT_EQ(move->first, 17);
  EXPECT_EQ(move->second, Vector3d(0.1, 0, -2));
  for (const char* text : {"0.1,0,-2", "x:1,2,3", ":1,2,3", "3:1,2", "3:1,2,nan"}) {
    EXPECT_EQ(ParseVertexMove(text).status().code(), absl::StatusCode::kInvalidArgument) << text;
  }
}

// The CLI11 checks pass good values and give the parser's message for bad
// ones.
TEST(PoseArgsTest, ValidatorsRunTheParsers) {
  std::string good = "1,2,3", bad = "1,2";
  EXPECT_EQ(Vector3Value()(good), "");
  EXPECT_NE(Vector3Value()(bad).find("expected 3 comma-separated numbers"), std::string::npos);
  std::string pose = "1,2,3,0,0,0";
  EXPECT_EQ(PoseValue()(pose), "");
  EXPECT_NE(PoseValue()(good), "");
  std::string four = "1,2,3,4";
  EXPECT_EQ(NumbersValue(4)(four), "");
  EXPECT_NE(NumbersValue(3)(four), "");
  std::string move = "2:1,2,3";
  EXPECT_EQ(VertexMoveValue()(move), "");
  EXPECT_NE(VertexMoveValue()(good), "");
}

}  // namespace
}  // namespace hs::cli

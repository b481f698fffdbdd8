#include "client/contact_command.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sstream>

#include "client/exit_codes.h"
#include "client/pose_args.h"
#include "tests/common/test_data_dir.h"

namespace hs::cli {
namespace {

const std::string kCube = hs::TestDataDir() + "/cube.obj";

// A unit cube sunk 0.01 into another along -z: depth 0.01, reversing vector
// +z, in the JSON the command prints for both methods; face on face for the
// 3D method (the paper's projections see an edge: two of the cube's bottom
// corners lie inside the other cube's projection in the chosen plane).
TEST(ContactCommandTest, CubeOnCubeJson) {
  for (const char* method : {"3d", "paper"}) {
    SCOPED_TRACE(method);
    std::ostringstream out, err;
    ContactArgs args{.moving_file = kCube,
                     .fixed_file = kCube,
                     .pose_moving = "0.2,0.3,0.99,0,0,0",
                     .direction = "0,0,-1",
                     .method = method,
                     .json = true};
    ASSERT_EQ(RunContact(args, out, err), kExitOk) << err.str();
    const auto j = nlohmann::json::parse(out.str());
    EXPECT_EQ(j["colliding"], true);
    EXPECT_NEAR(j["depth_m"].get<double>(), 0.01, 1e-12);
    EXPECT_NEAR(j["reversing_vector_W_m"][2].get<double>(), 0.01, 1e-12);
    if (std::string(method) == "3d") {
      EXPECT_EQ(j["moving"]["kind"], "face");
    }
  }
}

// --continuous treats the direction as the whole step: a cube stepping 3 m
// down through another from 1.5 m above first touches it after 1/6 of it.
TEST(ContactCommandTest, ContinuousReportsTimeOfImpact) {
  std::ostringstream out, err;
  ContactArgs args{.moving_file = kCube,
                   .fixed_file = kCube,
                   .pose_moving = "0.2,0.3,-1.5,0,0,0",
                   .direction = "0,0,-3",
                   .continuous = true,
                   .json = true};
  ASSERT_EQ(RunContact(args, out, err), kExitOk) << err.str();
  const auto j = nlohmann::json::parse(out.str());
  EXPECT_NEAR(j["time_of_impact"].get<double>(), 1.0 / 6, 1e-12);
  EXPECT_NEAR(j["depth_m"].get<double>(), 2.5, 1e-12);
}

// Bad numbers and unknown files fail with a message, never a crash.
TEST(ContactCommandTest, BadInputFails) {
  auto run = [](ContactArgs args) {
    std::ostringstream out, err;
    const int code = RunContact(args, out, err);
    EXPECT_FALSE(err.str().empty());
    return code;
  };
  EXPECT_EQ(run({.moving_file = kCube, .fixed_file = kCube, .direction = "0,0,nan"}), kExitFailure);
  EXPECT_EQ(run({.moving_file = kCube, .fixed_file = kCube, .direction = "0,0"}), kExitFailure);
  EXPECT_EQ(run({.moving_file = kCube,
                 .fixed_file = kCube,
                 .pose_moving = "0,0,0,1e300,1e300,1e300",
                 .direction = "0,0,-1"}),
            kExitFailure);
  EXPECT_EQ(run({.moving_file = "/missing.obj", .fixed_file = kCube, .direction = "0,0,-1"}),
            kExitFailure);
}

// Poses are translation plus rotation vector (axis times angle).
TEST(PoseArgsTest, RotationVector) {
  const Isometry3d X = *ParsePose("1,2,3,0,0,1.5707963267948966");
  EXPECT_TRUE(X.translation().isApprox(Vector3d(1, 2, 3)));
  EXPECT_TRUE((X.linear() * Vector3d::UnitX()).isApprox(Vector3d::UnitY(), 1e-12));
  EXPECT_FALSE(ParsePose("1,2,3").ok());
  EXPECT_FALSE(ParsePose("1,2,3,a,0,0").ok());
  EXPECT_FALSE(ParseVector3("inf,0,0").ok());
}

}  // namespace
}  // namespace hs::cli

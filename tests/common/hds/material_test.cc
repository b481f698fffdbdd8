#include "common/hds/material.h"

#include <gtest/gtest.h>

#include <limits>
#include <string>

namespace hs {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// The default material and the edges of each documented range are valid.
TEST(MaterialTest, DefaultAndBoundaryValuesAreValid) {
  EXPECT_TRUE(ValidateMaterial(Material{}).ok());
  EXPECT_TRUE(ValidateMaterial({.name = "edge",
                                .stiffness_n_per_m = 1e-9,
                                .damping_ns_per_m = 0,
                                .static_friction = 0,
                                .dynamic_friction = 0})
                  .ok());
  EXPECT_TRUE(ValidateMaterial({.static_friction = 0.7, .dynamic_friction = 0.7}).ok());
  EXPECT_TRUE(ValidateMaterial({.name = "hardest",
                                .stiffness_n_per_m = kMaxStiffnessNPerM,
                                .damping_ns_per_m = kMaxDampingNsPerM,
                                .static_friction = kMaxFriction,
                                .dynamic_friction = kMaxFriction})
                  .ok());
}

// Each field out of its range is INVALID_ARGUMENT naming the material and
// that field.
TEST(MaterialTest, EachFieldOutOfRangeIsNamed) {
  struct Case {
    Material material;
    const char* field;
  };
  const Case cases[] = {
      {{.stiffness_n_per_m = 0}, "stiffness_n_per_m"},
      {{.stiffness_n_per_m = -5}, "stiffness_n_per_m"},
      {{.stiffness_n_per_m = kInf}, "stiffness_n_per_m"},
      {{.stiffness_n_per_m = kNaN}, "stiffness_n_per_m"},
      {{.stiffness_n_per_m = 1.000001 * kMaxStiffnessNPerM}, "stiffness_n_per_m"},
      {{.stiffness_n_per_m = 1e308}, "stiffness_n_per_m"},
      {{.damping_ns_per_m = 1.000001 * kMaxDampingNsPerM}, "damping_ns_per_m"},
      {{.damping_ns_per_m = kInf}, "damping_ns_per_m"},
      {{.static_friction = 1.000001 * kMaxFriction}, "static_friction"},
      {{.damping_ns_per_m = -0.1}, "damping_ns_per_m"},
      {{.damping_ns_per_m = kNaN}, "damping_ns_per_m"},
      {{.static_friction = -1, .dynamic_friction = 0}, "static_friction"},
      {{.static_friction = kInf}, "static_friction"},
      {{.dynamic_friction = -0.2}, "dynamic_friction"},
      {{.dynamic_friction = kNaN}, "dynamic_friction"},
      {{.static_friction = 0.3, .dynamic_friction = 0.31}, "dynamic_friction"},
  };
  for (Case c : cases) {
    c.material.name = "steel";
    const absl::Status status = ValidateMaterial(c.material);
    EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument) << c.field;
    EXPECT_NE(status.message().find(std::string("'steel': ") + c.field), std::string::npos)
        << status;
  }
}

}  // namespace
}  // namespace hs

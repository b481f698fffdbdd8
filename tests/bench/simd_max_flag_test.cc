#include "tests/bench/simd_max_flag.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "hwy/targets.h"

namespace hs {
namespace {

std::vector<std::string> Args(int argc, char** argv) { return {argv, argv + argc}; }

TEST(SimdMaxFlagTest, CapsDispatchAtTheTargetNamedAndKeepsTheOtherArguments) {
  const std::vector<int64_t> targets = hwy::SupportedAndGeneratedTargets();
  ASSERT_FALSE(targets.empty());
  const int64_t worst = targets.back();
  std::string flag = std::string("--simd_max=") + hwy::TargetName(worst);
  std::string program = "bench", filter = "--benchmark_filter=x", out = "--benchmark_out=y";
  char* argv[] = {program.data(), filter.data(), flag.data(), out.data()};
  int argc = 4;
  std::string error;
  ASSERT_TRUE(TakeSimdMaxFlag(argc, argv, error)) << error;
  EXPECT_EQ(Args(argc, argv), (std::vector<std::string>{"bench", filter, out}));
  EXPECT_EQ(hwy::SupportedAndGeneratedTargets(), std::vector<int64_t>{worst});
  hwy::DisableTargets(0);
  EXPECT_EQ(hwy::SupportedAndGeneratedTargets(), targets);
}

TEST(SimdMaxFlagTest, RefusesATargetThisMachineDoesNotRunAndNamesThoseItDoes) {
  const std::vector<int64_t> targets = hwy::SupportedAndGeneratedTargets();
  std::string program = "bench", flag = "--simd_max=NEON";
  char* argv[] = {program.data(), flag.data()};
  int argc = 2;
  std::string error;
  EXPECT_FALSE(TakeSimdMaxFlag(argc, argv, error));
  EXPECT_NE(error.find("NEON is not a target"), std::string::npos) << error;
  EXPECT_NE(error.find(hwy::TargetName(targets.front())), std::string::npos) << error;
  EXPECT_EQ(hwy::SupportedAndGeneratedTargets(), targets);
}

TEST(SimdMaxFlagTest, WithoutTheFlagChangesNothing) {
  const std::vector<int64_t> targets = hwy::SupportedAndGeneratedTargets();
  std::string program = "bench", filter = "--benchmark_filter=x";
  char* argv[] = {program.data(), filter.data()};
  int argc = 2;
  std::string error;
  EXPECT_TRUE(TakeSimdMaxFlag(argc, argv, error));
  EXPECT_EQ(Args(argc, argv), (std::vector<std::string>{"bench", filter}));
  EXPECT_EQ(hwy::SupportedAndGeneratedTargets(), targets);
}

}  // namespace
}  // namespace hs

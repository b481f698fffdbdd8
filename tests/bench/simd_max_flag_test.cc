#include "tests/bench/simd_max_flag.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "hwy/targets.h"

namespace hs {
namespace {

// A command line as main() gets it, and what TakeSimdMaxFlag leaves of it.
struct CommandLine {
  std::vector<std::string> args;
  std::vector<char*> argv;
  int argc = 0;
  std::ostringstream err;

  explicit CommandLine(std::vector<std::string> a) : args(std::move(a)) {
    for (std::string& arg : args) argv.push_back(arg.data());
    argc = static_cast<int>(argv.size());
  }
  bool Take() { return TakeSimdMaxFlag(argc, argv.data(), err); }
  std::string Error() const { return err.str(); }
  std::vector<std::string> Left() const { return {argv.begin(), argv.begin() + argc}; }
};

TEST(SimdMaxFlagTest, CapsDispatchAtTheTargetNamedAndKeepsTheOtherArguments) {
  const std::vector<int64_t> targets = hwy::SupportedAndGeneratedTargets();
  ASSERT_FALSE(targets.empty());
  const int64_t worst = targets.back();
  CommandLine line({"bench", "--benchmark_filter=x",
                    std::string("--simd_max=") + hwy::TargetName(worst), "--benchmark_out=y"});
  ASSERT_TRUE(line.Take()) << line.Error();
  EXPECT_EQ(line.Left(),
            (std::vector<std::string>{"bench", "--benchmark_filter=x", "--benchmark_out=y"}));
  EXPECT_EQ(hwy::SupportedAndGeneratedTargets(), std::vector<int64_t>{worst});
  hwy::DisableTargets(0);
  EXPECT_EQ(hwy::SupportedAndGeneratedTargets(), targets);
}

TEST(SimdMaxFlagTest, RefusesATargetThisMachineDoesNotRunAndNamesThoseItDoes) {
  const std::vector<int64_t> targets = hwy::SupportedAndGeneratedTargets();
  CommandLine line({"bench", "--simd_max=NEON"});
  EXPECT_FALSE(line.Take());
  EXPECT_NE(line.Error().find("NEON is not a target"), std::string::npos) << line.Error();
  EXPECT_NE(line.Error().find(hwy::TargetName(targets.front())), std::string::npos) << line.Error();
  EXPECT_EQ(hwy::SupportedAndGeneratedTargets(), targets);
}

TEST(SimdMaxFlagTest, WithoutTheFlagChangesNothing) {
  const std::vector<int64_t> targets = hwy::SupportedAndGeneratedTargets();
  CommandLine line({"bench", "--benchmark_filter=x"});
  EXPECT_TRUE(line.Take());
  EXPECT_EQ(line.Left(), (std::vector<std::string>{"bench", "--benchmark_filter=x"}));
  EXPECT_EQ(hwy::SupportedAndGeneratedTargets(), targets);
}

}  // namespace
}  // namespace hs

#include "server/cpu_affinity.h"

#include <gtest/gtest.h>
#include <sched.h>

#include <algorithm>
#include <string>
#include <thread>
#include <vector>

namespace hs {
namespace {

// Lists as taskset -c and the kernel write them come back sorted, each CPU
// once, ranges spelled out.
TEST(CpuAffinityTest, ParsesNumbersAndRanges) {
  const std::vector<std::pair<std::string, std::vector<int>>> cases = {
      {"0", {0}},
      {"3", {3}},
      {"0-3", {0, 1, 2, 3}},
      {"2-2", {2}},
      {"0,2,4-5", {0, 2, 4, 5}},
      {"5,1-2,1", {1, 2, 5}},
      {"1023", {1023}},
  };
  for (const auto& [text, cpus] : cases) {
    const absl::StatusOr<std::vector<int>> parsed = ParseCpuList(text);
    ASSERT_TRUE(parsed.ok()) << text << ": " << parsed.status();
    EXPECT_EQ(*parsed, cpus) << text;
  }
}

// Anything else is INVALID_ARGUMENT naming the list: nothing is guessed.
TEST(CpuAffinityTest, RefusesMalformedLists) {
  for (const std::string text : {"", ",", "0,", ",0", "a", "0x1", "-1", "1-", "-", "3-1", "0--2",
                                 "1 ", " 1", "+1", "1.5", "1024", "99999999999", "0-1024"}) {
    const absl::StatusOr<std::vector<int>> parsed = ParseCpuList(text);
    EXPECT_EQ(parsed.status().code(), absl::StatusCode::kInvalidArgument) << "'" << text << "'";
    EXPECT_NE(parsed.status().message().find("'" + text + "'"), std::string::npos)
        << parsed.status();
  }
}

// The allowed set is the kernel's: it holds the CPU this thread runs on.
TEST(CpuAffinityTest, AllowedCpusHoldTheCurrentOne) {
  const std::vector<int> allowed = AllowedCpus();
  ASSERT_FALSE(allowed.empty());
  EXPECT_TRUE(std::is_sorted(allowed.begin(), allowed.end()));
  const int current = sched_getcpu();
  ASSERT_GE(current, 0);
  EXPECT_NE(std::find(allowed.begin(), allowed.end(), current), allowed.end());
  EXPECT_TRUE(CheckCpusAllowed(allowed).ok());
}

// A CPU outside the allowed set, or none, is refused and changes nothing.
TEST(CpuAffinityTest, RefusesCpusNotAllowed) {
  const std::vector<int> allowed = AllowedCpus();
  int outside = 0;
  while (std::find(allowed.begin(), allowed.end(), outside) != allowed.end()) ++outside;
  ASSERT_LT(outside, CPU_SETSIZE);
  std::thread([&] {
    const absl::Status status = RunOnCpus({allowed.front(), outside});
    EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument);
    EXPECT_NE(status.message().find("CPU " + std::to_string(outside)), std::string::npos) << status;
    EXPECT_EQ(RunOnCpus({}).code(), absl::StatusCode::kInvalidArgument);
    EXPECT_EQ(AllowedCpus(), allowed);
  }).join();
}

// The thread that asked, and every thread it starts afterwards, runs on
// the CPUs given; threads elsewhere keep theirs.
TEST(CpuAffinityTest, ThreadsStartedAfterwardsInheritTheCpus) {
  const std::vector<int> allowed = AllowedCpus();
  const std::vector<int> last = {allowed.back()};
  std::vector<int> pinned, child, current_cpu;
  std::thread([&] {
    ASSERT_TRUE(RunOnCpus(last).ok());
    pinned = AllowedCpus();
    std::thread([&] {
      child = AllowedCpus();
      current_cpu = {sched_getcpu()};
    }).join();
  }).join();
  EXPECT_EQ(pinned, last);
  EXPECT_EQ(child, last);
  EXPECT_EQ(current_cpu, last);
  EXPECT_EQ(AllowedCpus(), allowed);  // this thread was not asked
}

}  // namespace
}  // namespace hs

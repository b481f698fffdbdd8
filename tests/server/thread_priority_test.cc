#include "server/thread_priority.h"

#include <gtest/gtest.h>
#include <pthread.h>
#include <sched.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "server/scene_registry.h"
#include "tests/common/scratch_dir.h"
#include "tests/server/test_server.h"

namespace hs {
namespace {

int PolicyOf(pthread_t thread, int* priority) {
  int policy = -1;
  sched_param param{};
  pthread_getschedparam(thread, &policy, &param);
  *priority = param.sched_priority;
  return policy;
}

// The scheduling policy and priority of thread `tid` of this process.
int PolicyOfTask(int tid, int* priority) {
  sched_param param{};
  sched_getparam(tid, &param);
  *priority = param.sched_priority;
  return sched_getscheduler(tid);
}

// Priorities outside 1..99 are refused before the system is asked.
TEST(ThreadPriorityTest, RangeChecked) {
  for (const int priority : {-1, 0, 100}) {
    EXPECT_EQ(SetRealtimePriority(priority).code(), absl::StatusCode::kInvalidArgument);
    EXPECT_EQ(CheckRealtimePriority(priority).code(), absl::StatusCode::kInvalidArgument);
  }
}

// Where the system allows it, the calling thread runs under SCHED_FIFO at
// the priority asked; the check tries it on a thread of its own and leaves
// the caller's scheduling alone. Where it does not, both say
// PERMISSION_DENIED.
TEST(ThreadPriorityTest, SetsTheCallingThreadOnly) {
  int priority = 0;
  const int before = PolicyOf(pthread_self(), &priority);
  const absl::Status check = CheckRealtimePriority(10);
  EXPECT_EQ(PolicyOf(pthread_self(), &priority), before);
  if (check.code() == absl::StatusCode::kPermissionDenied) {
    EXPECT_EQ(SetRealtimePriority(10).code(), absl::StatusCode::kPermissionDenied);
    GTEST_SKIP() << "no real-time scheduling here: " << check.message();
  }
  ASSERT_TRUE(check.ok()) << check;
  std::thread t([] {
    ASSERT_TRUE(SetRealtimePriority(10).ok());
    int p = 0;
    EXPECT_EQ(PolicyOf(pthread_self(), &p), SCHED_FIFO);
    EXPECT_EQ(p, 10);
  });
  t.join();
}

// A server with a real-time priority steps its scenes on SCHED_FIFO
// threads: the scene's own thread, its workers and its frames thread,
// found by name.
TEST(ThreadPriorityTest, SceneThreadsRunRealtime) {
  if (!CheckRealtimePriority(7).ok()) GTEST_SKIP() << "no real-time scheduling here";
  ServerLimits limits;
  limits.threads_per_scene = 2;
  limits.realtime_priority = 7;
  Metrics metrics;
  SceneRegistry registry(limits, ScratchDir("models").string(), metrics);
  ASSERT_TRUE(registry.Create(testing::SmallScene("rt"), "").ok());
  // The threads take their scheduling as they start: wait for all, 2 s at most.
  std::vector<std::string> found;
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(2);
  while (found.size() < 3 && std::chrono::steady_clock::now() < give_up) {
    found.clear();
    for (const auto& task : std::filesystem::directory_iterator("/proc/self/task")) {
      std::ifstream comm(task.path() / "comm");
      std::string name;
      std::getline(comm, name);
      if (name != "scene-step" && name != "step-worker" && name != "scene-frames") continue;
      int priority = 0;
      if (PolicyOfTask(std::stoi(task.path().filename()), &priority) == SCHED_FIFO &&
          priority == 7) {
        found.push_back(name);
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  std::sort(found.begin(), found.end());
  EXPECT_EQ(found, (std::vector<std::string>{"scene-frames", "scene-step", "step-worker"}));
}

}  // namespace
}  // namespace hs

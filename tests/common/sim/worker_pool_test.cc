#include "common/sim/worker_pool.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>
#include <thread>
#include <vector>

namespace hs {
namespace {

// Every index of every job runs exactly once, whatever the number of
// threads and jobs, and ForEach returns only once all of them have run.
TEST(WorkerPoolTest, EachIndexRunsOnceBeforeReturn) {
  for (const int threads : {1, 2, 3, 8}) {
    WorkerPool pool(threads);
    EXPECT_EQ(pool.threads(), std::max(threads, 1));
    for (int job = 0; job < 2000; ++job) {
      const int n = job % 9;  // 0 and 1 included
      std::vector<std::atomic<int>> runs(n);
      pool.ForEach(n, [&](int i) { runs[i].fetch_add(1); });
      for (int i = 0; i < n; ++i) ASSERT_EQ(runs[i].load(), 1) << threads << " " << job << " " << i;
    }
  }
}

// With more than one thread, the tasks of one job do run at once: two tasks
// that each wait for the other both finish.
TEST(WorkerPoolTest, TasksRunAtOnce) {
  WorkerPool pool(2);
  std::atomic<int> arrived{0};
  pool.ForEach(2, [&](int) {
    arrived.fetch_add(1);
    while (arrived.load() < 2) std::this_thread::yield();
  });
  EXPECT_EQ(arrived.load(), 2);
}

// Each worker runs the start hook once, on itself, before it takes tasks;
// the calling thread never runs it.
TEST(WorkerPoolTest, StartHookRunsOnEachWorker) {
  std::mutex mu;
  std::vector<std::thread::id> started;
  {
    WorkerPool pool(3, [&] {
      std::lock_guard lock(mu);
      started.push_back(std::this_thread::get_id());
    });
    std::atomic<int> arrived{0};
    pool.ForEach(3, [&](int) {  // all three at once: both workers are up
      arrived.fetch_add(1);
      while (arrived.load() < 3) std::this_thread::yield();
    });
  }
  ASSERT_EQ(started.size(), 2u);
  EXPECT_NE(started[0], started[1]);
  for (const std::thread::id id : started) EXPECT_NE(id, std::this_thread::get_id());
}

// The thread of each task of a job of `n` tasks that each sleep `sleep`.
// With `meet`, each task then waits (2 s at most) until two have arrived,
// so that a job the workers take does run on two threads.
std::vector<std::thread::id> ThreadsOfJob(WorkerPool& pool, int n, std::chrono::microseconds sleep,
                                          bool meet) {
  std::vector<std::thread::id> ran_on(n);
  std::atomic<int> arrived{0};
  pool.ForEach(n, [&](int i) {
    ran_on[i] = std::this_thread::get_id();
    std::this_thread::sleep_for(sleep);
    arrived.fetch_add(1);
    const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(2);
    while (meet && arrived.load() < 2 && std::chrono::steady_clock::now() < give_up) {
      std::this_thread::yield();
    }
  });
  return ran_on;
}

bool AllOnCaller(const std::vector<std::thread::id>& ran_on) {
  return std::all_of(ran_on.begin(), ran_on.end(),
                     [](std::thread::id id) { return id == std::this_thread::get_id(); });
}

// With a threshold, jobs run on the calling thread alone until one takes
// longer than it; the next job is handed to the workers, and after a
// short one the calling thread is alone again. (A job handed over while
// it should not be would leave some of its eight 1 ms tasks to the
// worker.)
TEST(WorkerPoolTest, ShortJobsStayOnTheCaller) {
  WorkerPool pool(2);
  pool.set_serial_below(std::chrono::milliseconds(50));
  using std::chrono::microseconds;
  EXPECT_TRUE(AllOnCaller(ThreadsOfJob(pool, 8, microseconds(1000), false)));
  EXPECT_TRUE(AllOnCaller(ThreadsOfJob(pool, 8, microseconds(1000), false)));
  EXPECT_TRUE(AllOnCaller(ThreadsOfJob(pool, 2, microseconds(30000), false)));  // 60 ms
  EXPECT_FALSE(AllOnCaller(ThreadsOfJob(pool, 2, microseconds(0), true)));
  EXPECT_TRUE(AllOnCaller(ThreadsOfJob(pool, 8, microseconds(1000), false)));
}

// Fewer than one thread means the calling thread alone.
TEST(WorkerPoolTest, ZeroThreadsRunsOnCaller) {
  WorkerPool pool(0);
  EXPECT_EQ(pool.threads(), 1);
  const std::thread::id caller = std::this_thread::get_id();
  int ran = 0;
  pool.ForEach(3, [&](int) {
    EXPECT_EQ(std::this_thread::get_id(), caller);
    ++ran;
  });
  EXPECT_EQ(ran, 3);
}

}  // namespace
}  // namespace hs

#include "core/parallel.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <utility>
#include <vector>

namespace hexcal {
namespace {

TEST(ParallelWorkersTest, ZeroMeansEveryCoreAndNeverMoreThanTheItems) {
  EXPECT_EQ(ResolveThreadCount(3), 3);
  EXPECT_GE(ResolveThreadCount(0), 1);
  EXPECT_EQ(ParallelWorkers(100, 0), std::min(100, ResolveThreadCount(0)));
  EXPECT_EQ(ParallelWorkers(2, 8), 2);
  EXPECT_EQ(ParallelWorkers(0, 8), 1);
}

TEST(ParallelForTest, EachIndexOnceWhateverTheThreadCount) {
  for (int threads : {0, 1, 2, 5}) {
    std::vector<int> runs(1000, 0);
    const int workers = ParallelWorkers(1000, threads);
    ASSERT_TRUE(ParallelFor(1000, threads, [&](int index, int worker) {
      ++runs[index];
      EXPECT_LT(worker, workers);
    }));
    for (int index = 0; index < 1000; ++index) EXPECT_EQ(runs[index], 1) << "threads " << threads;
  }
}

// The kept threads serve one job at a time: a call nested in a job, or made
// from another thread meanwhile, runs on threads of its own.
TEST(ParallelForTest, NestedAndConcurrentCallsRunEachIndexOnce) {
  std::vector<std::atomic<int>> inner(8 * 100);
  std::vector<std::atomic<int>> outer(8);
  std::thread other([&] {
    for (int repeat = 0; repeat < 50; ++repeat) {
      std::vector<int> runs(64, 0);
      ASSERT_TRUE(ParallelFor(64, 2, [&](int index, int) { ++runs[index]; }));
      for (int k = 0; k < 64; ++k) ASSERT_EQ(runs[k], 1);
    }
  });
  ASSERT_TRUE(ParallelFor(8, 2, [&](int index, int) {
    ++outer[index];
    ParallelFor(100, 3, [&](int k, int worker) {
      EXPECT_LT(worker, 3);
      ++inner[index * 100 + k];
    });
  }));
  other.join();
  for (const std::atomic<int>& runs : outer) EXPECT_EQ(runs.load(), 1);
  for (const std::atomic<int>& runs : inner) EXPECT_EQ(runs.load(), 1);
}

// A body that throws on the calling thread: the exception comes out once the
// other threads are done with the body, and the next call runs as usual.
TEST(ParallelForTest, AnExceptionOnTheCallingThreadComesOut) {
  const auto body = [](int, int worker) {
    if (worker == 0) throw std::runtime_error("item failed");
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  };
  EXPECT_THROW(ParallelFor(100, 2, body), std::runtime_error);
  std::vector<int> runs(100, 0);
  ASSERT_TRUE(ParallelFor(100, 2, [&](int index, int) { ++runs[index]; }));
  for (int k = 0; k < 100; ++k) EXPECT_EQ(runs[k], 1);
}

// A forked child has none of the pool's threads: it runs on threads of its own.
TEST(ParallelForTest, AForkedChildRunsOnThreadsOfItsOwn) {
  ASSERT_TRUE(ParallelFor(10, 2, [](int, int) {}));  // the pool, if any, exists
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    std::vector<int> runs(100, 0);
    const bool finished = ParallelFor(100, 2, [&](int index, int) { ++runs[index]; });
    ::_exit(finished && std::count(runs.begin(), runs.end(), 1) == 100 ? 0 : 1);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
}

TEST(ParallelForTest, ProgressCountsEveryItemOneCallAtATime) {
  std::vector<int> calls;
  int in_progress = 0, overlaps = 0;
  JobHooks hooks;
  hooks.progress = [&](int done, int total) {
    if (++in_progress > 1) ++overlaps;
    EXPECT_EQ(total, 50);
    calls.push_back(done);
    --in_progress;
  };
  ASSERT_TRUE(ParallelFor(
      50, 4, [](int, int) {}, hooks));
  EXPECT_EQ(overlaps, 0);
  ASSERT_EQ(calls.size(), 50u);
  for (int k = 0; k < 50; ++k) EXPECT_EQ(calls[k], k + 1);
}

TEST(ParallelForTest, CancelSkipsTheRemainingItems) {
  std::atomic<bool> cancel{false};
  std::atomic<int> ran{0};
  JobHooks hooks;
  hooks.cancel = &cancel;
  const bool finished = ParallelFor(
      1000, 2,
      [&](int index, int) {
        ++ran;
        if (index == 10) cancel = true;
      },
      hooks);
  EXPECT_FALSE(finished);
  EXPECT_LT(ran.load(), 1000);
  EXPECT_TRUE(hooks.Cancelled());
}

TEST(ParallelForBlocksTest, BlocksCoverTheRangeOnceWithBoundsIndependentOfThreads) {
  for (int threads : {1, 3}) {
    std::vector<int> covered(2500, 0);
    std::vector<std::pair<int, int>> bounds(3);
    ParallelForBlocks(2500, 1024, threads, [&](int begin, int end) {
      bounds[begin / 1024] = {begin, end};
      for (int k = begin; k < end; ++k) ++covered[k];
    });
    EXPECT_EQ(bounds, (std::vector<std::pair<int, int>>{{0, 1024}, {1024, 2048}, {2048, 2500}}));
    for (int k = 0; k < 2500; ++k) ASSERT_EQ(covered[k], 1);
  }
}

TEST(JobHooksTest, EmptyHooksAreSafe) {
  const JobHooks hooks;
  EXPECT_FALSE(hooks.Cancelled());
  hooks.Progress(1, 2);  // no callback: nothing happens
}

}  // namespace
}  // namespace hexcal

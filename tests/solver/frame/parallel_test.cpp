#include "solver/frame/parallel.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

namespace galsculpt {
namespace {

// Every index exactly once, at any thread count and cost (chunks may be cut anywhere).
TEST(Parallel, EveryIndexRunsExactlyOnce) {
  const int before = threadCount();
  for (int threads : {1, 2, 3}) {
    setThreadCount(threads);
    EXPECT_EQ(threadCount(), threads);
    for (long cost : {1L, 50L, 100000L}) {
      for (int n : {0, 1, 7, 4097, 100000}) {
        std::vector<std::atomic<int>> hits(static_cast<size_t>(n));
        parallelFor(
            n, [&](int i) { hits[static_cast<size_t>(i)].fetch_add(1); }, cost);
        int wrong = 0;
        for (const auto& h : hits) wrong += h.load() != 1;
        EXPECT_EQ(wrong, 0) << threads << " threads, n " << n << ", cost " << cost;
      }
    }
  }
  setThreadCount(before);
}

// With two threads allowed a large loop uses more than the calling thread; with one, it runs
// on the caller alone.
TEST(Parallel, TheThreadCountBoundsTheThreadsThatRunALoop) {
  if (std::thread::hardware_concurrency() < 2) GTEST_SKIP() << "one core";
  const int before = threadCount();
  auto threadsUsed = [] {
    std::mutex m;
    std::set<std::thread::id> ids;
    parallelFor(
        64,
        [&](int) {
          std::this_thread::sleep_for(std::chrono::milliseconds(2));
          std::lock_guard<std::mutex> lock(m);
          ids.insert(std::this_thread::get_id());
        },
        1000000);
    return ids.size();
  };
  setThreadCount(1);
  EXPECT_EQ(threadsUsed(), 1u);
  setThreadCount(2);
  EXPECT_EQ(threadsUsed(), 2u);
  setThreadCount(before);
}

TEST(Parallel, ZeroGoesBackToTheDefaultAndNegativeIsRefused) {
  const int before = threadCount();
  setThreadCount(5);
  setThreadCount(0);
  EXPECT_EQ(threadCount(), defaultThreadCount());
  EXPECT_THROW(setThreadCount(-1), std::invalid_argument);
  EXPECT_FALSE(defaultThreadSource().empty());
  setThreadCount(before);
}

}  // namespace
}  // namespace galsculpt

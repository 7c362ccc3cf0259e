// The CPU executor (solver/frame/cpu_executor.h): launches over independent items, reductions
// in fixed blocks whatever the thread count, and inside a captured section the refusal of
// everything the CUDA executor cannot record in a graph (reads, downloads, waits).
#include "solver/frame/cpu_executor.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "solver/frame/parallel.h"

namespace galsculpt {
namespace {

TEST(CpuExecutor, ForEachRunsEveryItemOnceAndCountsTheLaunch) {
  CpuExecutor ex;
  std::vector<int> hits(10000, 0);
  int* h = hits.data();
  ex.forEach(10000, [=](int i) { ++h[i]; });
  for (int v : hits) ASSERT_EQ(v, 1);
  EXPECT_EQ(ex.counters().launches, 1);
}

// Sums add 256-item blocks, then the blocks in order: the same bits for any thread count, and
// the bits of that order written out by hand.
TEST(CpuExecutor, SumsAreTheFixedBlockOrderForAnyThreadCount) {
  const int n = 5000;
  std::vector<double> v(n);
  for (int i = 0; i < n; ++i) v[i] = std::sin(0.37 * i) * std::pow(10.0, i % 7 - 3);
  const double* values = v.data();
  double expected = 0.0;
  for (int b = 0; b < n; b += 256) {
    double block = 0.0;
    for (int i = b; i < std::min(n, b + 256); ++i) block += v[i];
    expected += block;
  }
  for (const int threads : {1, 2, 3}) {
    setThreadCount(threads);
    CpuExecutor ex;
    double sum = 0.0, most = 0.0;
    ex.sum(
        n, [=](int i) { return values[i]; }, &sum);
    ex.maximum(
        n, [=](int i) { return values[i]; }, &most);
    EXPECT_EQ(sum, expected) << threads << " threads";
    EXPECT_EQ(most, *std::max_element(v.begin(), v.end()));
  }
  setThreadCount(0);
  CpuExecutor ex;
  double none = 0.0;
  ex.maximum(
      0, [](int) { return 1.0; }, &none);
  EXPECT_EQ(none, -std::numeric_limits<double>::infinity());
}

TEST(CpuExecutor, ACapturedSectionRefusesReadsDownloadsAndWaits) {
  CpuExecutor ex;
  std::vector<double> device = {1.0, 2.0}, host(2, 0.0);
  double a[1] = {4.0}, failed = -1.0;
  ex.captured(0, 1, [&] {
    EXPECT_THROW(ex.read(device.data(), host.data(), 2), std::logic_error);
    EXPECT_THROW(ex.download(device.data(), host.data(), 2), std::logic_error);
    EXPECT_THROW(ex.denseCholesky(1, a, &failed), std::logic_error);
    ex.copy(host.data(), device.data(), 2);  // a device copy is recorded, not refused
  });
  EXPECT_EQ(host, device);
  // Outside the section everything is allowed again.
  ex.read(device.data(), host.data(), 2);
  EXPECT_TRUE(ex.denseCholesky(1, a, &failed));
  EXPECT_DOUBLE_EQ(a[0], 2.0);
  EXPECT_EQ(failed, 0.0);
}

// A dense factorization leaves its status where the frame's next read finds it: no wait of its
// own, and 1 for a matrix that is not positive definite.
TEST(CpuExecutor, ADenseFactorizationLeavesItsStatusWithoutAWait) {
  CpuExecutor ex;
  double indefinite[4] = {1.0, 2.0, 2.0, 1.0}, failed = 0.0;
  const long waits = ex.counters().waits;
  EXPECT_TRUE(ex.denseCholesky(2, indefinite, &failed));
  EXPECT_EQ(failed, 1.0);
  EXPECT_EQ(ex.counters().waits, waits);
}

// The launches between two host waits are one device program (one kernel on a GPU), each
// launch a phase ending at a grid barrier (a reduction two), a device loop's test a barrier of
// its own; a read, a download, an upload or flush() ends the program.
TEST(CpuExecutor, LaunchesBetweenTwoWaitsAreOneProgramOfPhases) {
  CpuExecutor ex;
  ex.flush();
  std::vector<double> v(300, 1.0), w(300, 0.0);
  double* p = v.data();
  double* q = w.data();
  double total = 0.0;
  const DeviceCounters start = ex.counters();
  ex.forEach(300, [=](int i) { p[i] *= 2.0; });
  ex.sum(
      300, [=](int i) { return p[i]; }, &total);
  ex.copy(q, p, 300);
  double read = 0.0;
  ex.read(&total, &read, 1);
  DeviceCounters now = ex.counters();
  EXPECT_EQ(now.programs - start.programs, 1);
  EXPECT_EQ(now.barriers - start.barriers, 1 + 2 + 1);
  EXPECT_EQ(read, 600.0);
  // A loop of three passes after the read: a second program, its test a barrier before the
  // first pass and after each.
  double running = 1.0, passes = 0.0;
  double* flag = &running;
  double* count = &passes;
  ex.loopOnDevice(1, flag, 10, [&] {
    ex.forEach(1, [=](int) {
      *count += 1.0;
      if (*count >= 3.0) *flag = 0.0;
    });
  });
  ex.flush();
  const DeviceCounters end = ex.counters();
  EXPECT_EQ(passes, 3.0);
  EXPECT_EQ(end.programs - now.programs, 1);
  EXPECT_EQ(end.barriers - now.barriers, 1 + 3 * (1 + 1));
  EXPECT_EQ(end.waits - now.waits, 0) << "the loop's test waits for nothing";
}

}  // namespace
}  // namespace galsculpt

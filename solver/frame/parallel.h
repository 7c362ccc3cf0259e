// How the CPU's parallel loops share the cores. Every parallel loop of the CPU backend (the
// executor's launches and reductions, assembly, the knife's edge test) goes through
// parallelFor, which runs on oneTBB's work-stealing scheduler: a loop is cut into chunks that
// idle threads take from busy ones, so a thread that the OS preempts (the window's thread, a
// compositor, another program on a busy desktop) holds up at most the chunk it is in, not a
// fixed half of the loop, and a thread with nothing to do sleeps instead of spinning against the
// others.
// Results never depend on the chunking or the thread count: each index writes only its own
// outputs, and reductions (cpu_executor.h) add fixed blocks in a fixed order.
//
// The thread count is chosen once per process (docs/cli.md, "Threads"): GALSCULPT_THREADS,
// else OMP_NUM_THREADS (scripts written for the OpenMP build), else every core the process may
// run on; `--threads N` and setThreadCount override it.
#pragma once

#include <string>

namespace galsculpt {

// Threads the CPU's parallel loops may use (>= 1).
int threadCount();
// n >= 1 threads from now on; n == 0 goes back to the default. Throws std::invalid_argument on
// n < 0. Not while a parallel loop runs.
void setThreadCount(int n);
// The default and where it came from ("GALSCULPT_THREADS", "OMP_NUM_THREADS" or "cores").
int defaultThreadCount();
std::string defaultThreadSource();

namespace detail {
using RangeBody = void (*)(const void* closure, int begin, int end);
// body(closure, begin, end) over chunks covering [0, n) once; `cost` as in parallelFor.
void parallelRanges(int n, long cost, RangeBody body, const void* closure);
}  // namespace detail

// Below this much work (items x cost) a loop runs on the calling thread: waking others costs more.
inline constexpr long kParallelWork = 4096;

// f(i) for every i in [0, n), in parallel. `cost`: about how many operations one item takes, so
// that few heavy items are cut as finely as many light ones.
template <typename F>
void parallelFor(int n, const F& f, long cost = 1) {
  if (n <= 0) return;
  cost = cost < 1 ? 1 : cost;
  if (n == 1 || static_cast<long>(n) * cost <= kParallelWork || threadCount() == 1) {
    for (int i = 0; i < n; ++i) f(i);
    return;
  }
  detail::parallelRanges(
      n, cost,
      [](const void* c, int begin, int end) {
        const F& g = *static_cast<const F*>(c);
        for (int i = begin; i < end; ++i) g(i);
      },
      &f);
}

}  // namespace galsculpt

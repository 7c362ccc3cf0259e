#include "solver/frame/parallel.h"

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/global_control.h>
#include <oneapi/tbb/info.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <memory>
#include <mutex>
#include <stdexcept>

namespace galsculpt {

namespace {

struct Default {
  int threads = 1;
  std::string source;
};

// A positive integer from the environment, or 0.
int positiveFromEnv(const char* name) {
  const char* text = std::getenv(name);
  if (!text || !*text) return 0;
  char* end = nullptr;
  const long v = std::strtol(text, &end, 10);
  return (*end == '\0' && v > 0 && v < 4096) ? static_cast<int>(v) : 0;
}

const Default& defaults() {
  static const Default d = [] {
    Default r;
    if (const int n = positiveFromEnv("GALSCULPT_THREADS")) {
      r = {n, "GALSCULPT_THREADS"};
    } else if (const int m = positiveFromEnv("OMP_NUM_THREADS")) {
      r = {m, "OMP_NUM_THREADS"};
    } else {
      // The cores this process may run on (its affinity mask and cgroup), not the machine's.
      r = {std::max(1, tbb::info::default_concurrency()), "cores"};
    }
    return r;
  }();
  return d;
}

std::mutex controlMutex;
std::unique_ptr<tbb::global_control> control;  // the limit in force, once set
// Every loop runs in this one arena, whoever calls it. Without it each calling thread gets an
// implicit arena of its own, and when that thread ends (the window runs each frame on a thread
// of its own) oneTBB tears the worker threads down with it: every frame started new ones.
std::unique_ptr<tbb::task_arena> arena;
std::atomic<int> current{0};  // 0: not set yet

void setLocked(int n) {
  arena.reset();
  control.reset();
  control = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                  static_cast<size_t>(n));
  current.store(n, std::memory_order_release);
}

// Made at the first loop, not before: a process that forks (bench) must not hold workers then.
tbb::task_arena& loopArena() {
  std::lock_guard<std::mutex> lock(controlMutex);
  if (!arena) arena = std::make_unique<tbb::task_arena>(current.load());
  return *arena;
}

}  // namespace

int threadCount() {
  const int n = current.load(std::memory_order_acquire);
  if (n > 0) return n;
  std::lock_guard<std::mutex> lock(controlMutex);
  if (current.load() == 0) setLocked(defaults().threads);
  return current.load();
}

void setThreadCount(int n) {
  if (n < 0) throw std::invalid_argument("a thread count must be at least 1");
  std::lock_guard<std::mutex> lock(controlMutex);
  setLocked(n == 0 ? defaults().threads : n);
}

int defaultThreadCount() {
  return defaults().threads;
}

std::string defaultThreadSource() {
  return defaults().source;
}

namespace detail {

void parallelRanges(int n, long cost, RangeBody body, const void* closure) {
  threadCount();  // the limit is in force before the first loop
  // auto_partitioner: a few chunks a thread to start, cut further only where a thread runs out
  // of work and steals (a preempted thread's share goes to the others). Chunks never go below
  // about kMinChunkWork operations, where taking one would cost as much as running it.
  constexpr long kMinChunkWork = 1024;
  const long grain = std::clamp(kMinChunkWork / cost, 1L, static_cast<long>(n));
  loopArena().execute([&] {
    tbb::parallel_for(
        tbb::blocked_range<int>(0, n, static_cast<size_t>(grain)),
        [&](const tbb::blocked_range<int>& r) { body(closure, r.begin(), r.end()); },
        tbb::auto_partitioner());
  });
}

}  // namespace detail

}  // namespace galsculpt

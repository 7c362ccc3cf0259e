// The CPU executor: buffers are vectors, a launch is a parallel loop (parallel.h: oneTBB's
// work stealing) over independent items (each writes only its own outputs), so the frame
// (frame_solver.h) gives bit-identical results for any thread count. Reductions add fixed blocks of
// 256 items and then the block sums in order, as the CUDA executor does. The CPU backend is the
// frame on this executor.
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <source_location>
#include <stdexcept>
#include <string>
#include <vector>

#include "solver/frame/device_counters.h"
#include "solver/frame/download_span.h"
#include "solver/frame/parallel.h"
#include "solver/frame/wait_sites.h"

namespace galsculpt {

namespace detail {
// Set while a captured section runs: what the CUDA executor records as a graph may not read
// from the device, allocate or wait, and the CPU executor enforces that for the tests.
inline thread_local bool capturing = false;
inline void forbidInCapture(const char* what) {
  if (capturing) throw std::logic_error(std::string(what) + " inside a captured section");
}
// A host synchronization or a buffer's change: the device program open ends there.
inline void endProgram(const char* what) {
  forbidInCapture(what);
  closeOpenProgram();
}
}  // namespace detail

// Marks a captured section (or a device loop's body) for its lifetime; sections do not nest.
struct CaptureFlag {
  CaptureFlag() {
    detail::forbidInCapture("a captured section");
    detail::capturing = true;
  }
  ~CaptureFlag() { detail::capturing = false; }
  CaptureFlag(const CaptureFlag&) = delete;
  CaptureFlag& operator=(const CaptureFlag&) = delete;
};

class CpuExecutor {
 public:
  static constexpr const char* kName = "cpu";
  // Buffers live in host memory: the frame may hand them to host libraries (CHOLMOD).
  static constexpr bool kHostMemory = true;
  template <typename T>
  class Buffer {
   public:
    T* data() { return v_.data(); }
    const T* data() const { return v_.data(); }
    size_t size() const { return v_.size(); }
    void resize(size_t n) {  // zeroed
      detail::endProgram("an allocation");
      v_.assign(n, T{});
    }
    void upload(const T* src, size_t n) {
      detail::endProgram("an upload");
      detail::transfers.hostToDevice += static_cast<double>(n * sizeof(T));
      v_.assign(src, src + n);
    }
    void upload(const std::vector<T>& src) { upload(src.data(), src.size()); }
    // Takes the host array over (on this executor, without a copy); `src` is left empty.
    void adopt(std::vector<T>&& src) {
      detail::endProgram("an upload");
      detail::transfers.hostToDevice += static_cast<double>(src.size() * sizeof(T));
      v_ = std::move(src);
      src = std::vector<T>();
    }
    void download(T* dst, size_t n) const {
      detail::endProgram("a download");
      detail::transfers.deviceToHost += static_cast<double>(n * sizeof(T));
      std::copy(v_.begin(), v_.begin() + n, dst);
    }

   private:
    std::vector<T> v_;
  };

  // A read-only view of host memory the model owns (SimModel's arrays): on this executor the
  // frame reads the model's own arrays, without a copy; the CUDA executor uploads them once.
  // The model must outlive the mirror (a frame solver refers to its model).
  template <typename T>
  class Mirror {
   public:
    void mirror(const T* src, size_t n) {
      detail::endProgram("an upload");
      detail::transfers.hostToDevice += static_cast<double>(n * sizeof(T));
      p_ = src;
      n_ = n;
    }
    void mirror(const std::vector<T>& src) { mirror(src.data(), src.size()); }
    const T* data() const { return p_; }
    size_t size() const { return n_; }

   private:
    const T* p_ = nullptr;
    size_t n_ = 0;
  };

  // What a frame costs a device (device_counters.h): counted here too, so that the CUDA path's
  // counts are known without a GPU (on the device-like executor, whose paths are the CUDA
  // executor's).
  using Counters = DeviceCounters;
  Counters counters() const {
    Counters c = counters_;
    c.hostToDeviceBytes = detail::transfers.hostToDevice;
    c.deviceToHostBytes = detail::transfers.deviceToHost + readBytes_;
    return c;
  }

  // `cost`: about how many operations one item takes, so that few heavy items (coarse blocks,
  // handles) are spread over the threads as well as many light ones; results do not depend on
  // it (every item writes its own outputs).
  template <typename F>
  void forEach(int n, const F& f, long cost = 1) const {
    countLaunch();
    parallelFor(n, f, cost);
  }
  // *out = sum of f(i) over i < n.
  template <typename F>
  void sum(int n, const F& f, double* out) const {
    reduce(n, f, out, 0.0, [](double a, double b) { return a + b; });
  }
  // *out = max of f(i) over i < n (-infinity when n is 0).
  template <typename F>
  void maximum(int n, const F& f, double* out) const {
    reduce(n, f, out, -std::numeric_limits<double>::infinity(),
           [](double a, double b) { return a > b ? a : b; });
  }
  template <typename T>
  void copy(T* dst, const T* src, size_t n) const {
    countPhase(counters_.copies, 1);
    std::memmove(dst, src, n * sizeof(T));
  }
  template <typename T>
  void read(const T* deviceValues, T* host, int n,
            std::source_location site = std::source_location::current()) const {
    detail::endProgram("a host read");
    countWait(site);
    ++counters_.reads;
    ++counters_.waits;
    readBytes_ += static_cast<double>(n * sizeof(T));
    std::copy(deviceValues, deviceValues + n, host);
  }
  // Device to host (the CUDA executor's pinned path).
  template <typename T>
  void download(const T* device, T* host, size_t n,
                std::source_location site = std::source_location::current()) const {
    detail::endProgram("a download");
    countWait(site);
    ++counters_.waits;
    readBytes_ += static_cast<double>(n * sizeof(T));
    std::copy(device, device + n, host);
  }
  // Several arrays device to host behind one wait (a frame's positions and velocities).
  void downloadAll(std::initializer_list<DownloadSpan> spans,
                   std::source_location site = std::source_location::current()) const {
    detail::endProgram("a download");
    countWait(site);
    ++counters_.waits;
    for (const DownloadSpan& s : spans) {
      readBytes_ += static_cast<double>(s.bytes);
      if (s.bytes) std::memcpy(s.host, s.device, s.bytes);
    }
  }
  // In-place dense Cholesky (lower, column-major). Its status goes to *failed (executor memory:
  // 1 where the matrix is not positive definite), where the frame reads it with its next read:
  // no wait of its own. False where it cannot run (the CUDA executor without cuSOLVER). A
  // library's call on the device: it ends the program open and counts as two kernels, as the
  // CUDA executor runs it (cuSOLVER's call, counted as one though it launches a few, and the
  // status's copy).
  bool denseCholesky(int n, double* a, double* failed) const {
    detail::endProgram("a dense factorization (a library's call)");
    counters_.programs += 2;
    Eigen::Map<Eigen::MatrixXd> m(a, n, n);
    Eigen::LLT<Eigen::Ref<Eigen::MatrixXd>> llt(m);
    *failed = llt.info() == Eigen::Success ? 0.0 : 1.0;
    return true;
  }
  // inverse = (L Lᵀ)⁻¹ from denseCholesky's factor L (column-major, n x n). A library's call on
  // the device: it ends the program open and counts as two kernels, with no wait (the
  // identity's fill, and cuSOLVER's two triangular solves on it, counted as one).
  void denseCholeskyInverse(int n, const double* l, double* inverse) const {
    detail::endProgram("a dense inverse (a library's call)");
    counters_.programs += 2;
    const Eigen::Map<Eigen::MatrixXd> m(const_cast<double*>(l), n, n);  // read only
    Eigen::Map<Eigen::MatrixXd> x(inverse, n, n);
    x.setIdentity();
    m.triangularView<Eigen::Lower>().solveInPlace(x);
    m.triangularView<Eigen::Lower>().transpose().solveInPlace(x);
  }
  // A section of launches only (no reads, no allocations), each a phase of the device program
  // open; here it just runs, and a read inside it throws (the tests' guard of what a device may
  // not do there).
  template <typename Body>
  void captured(int /*slot*/, std::uint64_t /*key*/, const Body& body) {
    const CaptureFlag flag;
    body();
  }
  // A loop whose test the device makes: `body` (launches only) runs while *running is not 0,
  // tested before each pass, at most `mostPasses` passes. On a device the test is a phase of the
  // program open, so the host waits for nothing; here the flag is read where it lies (no wait is
  // counted: on a device no one waits for it), and each test counts its barrier. The body must
  // bake nothing a pass changes: every pass replays the same launches.
  template <typename Body>
  void loopOnDevice(std::uint64_t /*key*/, const double* running, int mostPasses,
                    const Body& body) const {
    const CaptureFlag flag;
    countLoopTest();
    for (int pass = 0; pass < mostPasses && *running != 0.0; ++pass) {
      body();
      countLoopTest();
    }
  }
  // Ends the device program open (the end of a frame: it runs while the host goes on).
  void flush() const { detail::closeOpenProgram(); }
  void synchronize() const { detail::endProgram("a synchronization"); }

 protected:
  // A launch: a phase of the device program open, which it opens where none is (the device
  // runs the launches between two host synchronizations as one kernel: gpu/device_program.cuh).
  void countLaunch() const { countPhase(counters_.launches, 1); }
  void countPhase(long& asked, int barriers) const {
    ++asked;
    counters_.barriers += barriers;
    openProgram();
  }
  // Where a device would wait, by source line, for GALSCULPT_WAIT_SITES (wait_sites.h).
  void countWait(const std::source_location& site) const {
    if (waitSites_) detail::WaitSites::instance().add(site);
  }
  void countLoopTest() const {
    ++counters_.barriers;
    openProgram();
  }
  void openProgram() const {
    if (detail::openProgram.executor == this) return;
    detail::closeOpenProgram();
    ++counters_.programs;
    detail::openProgram = {[](void*) {}, const_cast<CpuExecutor*>(this)};
  }

 private:
  mutable Counters counters_;
  bool waitSites_ = detail::WaitSites::instance().enabled();
  mutable double readBytes_ = 0.0;  // host reads and downloads

  template <typename F, typename Op>
  void reduce(int n, const F& f, double* out, double identity, const Op& op) const {
    countPhase(counters_.reductions, 2);
    constexpr int kBlock = 256;
    const int blocks = (n + kBlock - 1) / kBlock;
    std::vector<double> partial(blocks, identity);
    parallelFor(
        blocks,
        [&](int b) {
          double acc = identity;
          const int end = std::min(n, (b + 1) * kBlock);
          for (int i = b * kBlock; i < end; ++i) acc = op(acc, f(i));
          partial[b] = acc;
        },
        kBlock);
    double total = identity;
    for (double p : partial) total = op(total, p);
    *out = total;
  }
};

}  // namespace galsculpt

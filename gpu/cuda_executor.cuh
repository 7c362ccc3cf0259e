// The device solver's executor on a CUDA GPU: buffers in device memory; the launches between two
// host synchronizations recorded as a device program and run as one cooperative kernel whose
// phases meet at grid-wide barriers (device_program.cuh), device loops a jump inside it;
// deterministic two-pass reductions (a fixed partition of the items, then one block); the dense
// coarse Cholesky through cuSOLVER (loaded on first use); reads through a pinned staging buffer.
// Where a GPU cannot launch cooperatively, or GALSCULPT_CUDA_PROGRAMS=0, each launch is a kernel
// of its own, captured sections are recorded once as CUDA graphs and replayed while their key
// holds, and device loops are graphs with a while node. Everything runs on the per-thread default
// stream (capturable, and no stream handle to pass to buffers).
//
// Every CUDA call is checked: a failure throws CudaError naming the call, file and line.
#pragma once

#include <cuda_runtime.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <memory>
#include <typeinfo>

#include "gpu/cuda_check.h"
#include "gpu/cusolver_loader.h"
#include "gpu/device_program.cuh"
#include "gpu/launch_profile.h"
#include "solver/frame/device_counters.h"
#include "solver/frame/download_span.h"

namespace galsculpt::gpu {

template <typename F>
__global__ void forEachKernel(int n, F f) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n) f(i);
}

#if CUDART_VERSION >= 12040
// A device loop's tests (CudaExecutor::loopOnDevice; static: one copy a source file): the while
// node's condition from the flag, before the first pass and after each, within the passes
// allowed. passes[0] counts every pass the loop ever made (counters() reads it), passes[1] where
// this launch started.
static __global__ void loopEntryKernel(cudaGraphConditionalHandle handle, const double* running,
                                       long long* passes) {
  passes[1] = passes[0];
  cudaGraphSetConditional(handle, *running != 0.0 ? 1u : 0u);
}
static __global__ void loopTestKernel(cudaGraphConditionalHandle handle, const double* running,
                                      long long* passes, int mostPasses) {
  const long long done = ++passes[0] - passes[1];
  cudaGraphSetConditional(handle, *running != 0.0 && done < mostPasses ? 1u : 0u);
}
#endif

// Pass one: each block reduces a fixed, strided share of the items into partial[block].
template <typename F, typename Op>
__global__ void reduceKernel(int n, F f, Op op, double identity, double* partial) {
  double acc = identity;
  for (int i = blockIdx.x * blockDim.x + threadIdx.x; i < n; i += gridDim.x * blockDim.x)
    acc = op(acc, f(i));
  __shared__ double shared[kThreads];
  const double total = blockReduceIn(shared, acc, op);
  if (threadIdx.x == 0) partial[blockIdx.x] = total;
}

// Pass two: one block reduces the partials in a fixed order.
template <typename Op>
__global__ void finishKernel(int blocks, const double* partial, Op op, double identity,
                             double* out) {
  double acc = identity;
  for (int i = threadIdx.x; i < blocks; i += blockDim.x) acc = op(acc, partial[i]);
  __shared__ double shared[kThreads];
  const double total = blockReduceIn(shared, acc, op);
  if (threadIdx.x == 0) *out = total;
}

// Pinned host memory for device-to-host copies (positions every frame, scalars every Newton
// iteration): DMA straight into it, then one memcpy. Owned by the executor: the app runs each
// frame on a fresh worker thread, and pinning memory per thread would cost milliseconds a frame.
class PinnedStaging {
 public:
  PinnedStaging() = default;
  PinnedStaging(const PinnedStaging&) = delete;
  PinnedStaging& operator=(const PinnedStaging&) = delete;
  ~PinnedStaging() {
    if (data_) cudaFreeHost(data_);
  }
  void* get(size_t bytes) {
    if (bytes > bytes_) {
      if (data_) GALSCULPT_CUDA_CHECK(cudaFreeHost(data_));
      data_ = nullptr;
      GALSCULPT_CUDA_CHECK(cudaMallocHost(&data_, bytes));
      bytes_ = bytes;
    }
    return data_;
  }

 private:
  void* data_ = nullptr;
  size_t bytes_ = 0;
};

class CudaExecutor {
 public:
  static constexpr const char* kName = "cuda";
  static constexpr bool kHostMemory = false;

  template <typename T>
  class Buffer {
   public:
    Buffer() = default;
    Buffer(const Buffer&) = delete;
    Buffer& operator=(const Buffer&) = delete;
    Buffer(Buffer&& other) noexcept : p_(other.p_), n_(other.n_) {
      other.p_ = nullptr;
      other.n_ = 0;
    }
    Buffer& operator=(Buffer&& other) noexcept {
      std::swap(p_, other.p_);
      std::swap(n_, other.n_);
      return *this;
    }
    ~Buffer() {
      if (!p_) return;
      try {
        ::galsculpt::detail::closeOpenProgram();  // its launches may still read this memory
      } catch (const CudaError&) {
        // A failed launch here has no one to tell: the device's next call reports its state.
      }
      cudaFree(p_);
    }
    T* data() { return p_; }
    const T* data() const { return p_; }
    size_t size() const { return n_; }
    // Setup only (never inside a captured section): synchronous, so that a frame launched later
    // from another thread (the app's worker) sees the zeros.
    void resize(size_t n) {
      ::galsculpt::detail::closeOpenProgram();
      allocate(n);
      if (n) GALSCULPT_CUDA_CHECK(cudaMemsetAsync(p_, 0, n * sizeof(T), GALSCULPT_CUDA_STREAM));
      GALSCULPT_CUDA_CHECK(cudaStreamSynchronize(GALSCULPT_CUDA_STREAM));
    }
    void upload(const T* src, size_t n) {
      ::galsculpt::detail::closeOpenProgram();
      ::galsculpt::detail::transfers.hostToDevice += static_cast<double>(n * sizeof(T));
      allocate(n);
      if (n)
        GALSCULPT_CUDA_CHECK(
            cudaMemcpyAsync(p_, src, n * sizeof(T), cudaMemcpyHostToDevice, GALSCULPT_CUDA_STREAM));
      GALSCULPT_CUDA_CHECK(cudaStreamSynchronize(GALSCULPT_CUDA_STREAM));  // src may go away
    }
    void upload(const std::vector<T>& src) { upload(src.data(), src.size()); }
    // Uploads and frees the host array (the CPU executor takes it over instead).
    void adopt(std::vector<T>&& src) {
      upload(src);
      src = std::vector<T>();
    }
    // Setup and rare transfers; per-frame ones go through CudaExecutor::download (pinned).
    void download(T* dst, size_t n) const {
      if (!n) return;
      ::galsculpt::detail::closeOpenProgram();
      ::galsculpt::detail::transfers.deviceToHost += static_cast<double>(n * sizeof(T));
      GALSCULPT_CUDA_CHECK(cudaMemcpyAsync(static_cast<void*>(dst), p_, n * sizeof(T),
                                           cudaMemcpyDeviceToHost, GALSCULPT_CUDA_STREAM));
      GALSCULPT_CUDA_CHECK(cudaStreamSynchronize(GALSCULPT_CUDA_STREAM));
    }

   private:
    void allocate(size_t n) {
      if (n == n_) return;
      if (p_) GALSCULPT_CUDA_CHECK(cudaFree(p_));
      p_ = nullptr;
      n_ = n;
      if (n) GALSCULPT_CUDA_CHECK(cudaMalloc(&p_, n * sizeof(T)));
    }
    T* p_ = nullptr;
    size_t n_ = 0;
  };

  // The model's arrays, uploaded once (the CPU executor reads them where they are).
  template <typename T>
  class Mirror {
   public:
    void mirror(const T* src, size_t n) { buffer_.upload(src, n); }
    void mirror(const std::vector<T>& src) { buffer_.upload(src); }
    const T* data() const { return buffer_.data(); }
    size_t size() const { return buffer_.size(); }

   private:
    Buffer<T> buffer_;
  };

  // `programs`: record device programs where the GPU can run them (and
  // GALSCULPT_CUDA_PROGRAMS is not 0); false, a kernel per launch (the checks' comparison).
  explicit CudaExecutor(bool programs = true) {
    GALSCULPT_CUDA_CHECK(cudaMalloc(&partial_, kReduceBlocks * sizeof(double)));
    GALSCULPT_CUDA_CHECK(cudaMalloc(&info_, sizeof(int)));
    const char* graphs = std::getenv("GALSCULPT_CUDA_GRAPHS");
    graphs_ = !(graphs && std::string(graphs) == "0");
    const char* wanted = std::getenv("GALSCULPT_CUDA_PROGRAMS");
    programs_ = programs && graphs_ && !(wanted && std::string(wanted) == "0") && runner_.start();
    if (LaunchProfile::requested()) {
      profile_ = std::make_unique<LaunchProfile>();
      graphs_ = programs_ = false;  // each launch is waited for
    }
  }
  ~CudaExecutor() {
    if (::galsculpt::detail::openProgram.executor == this)
      ::galsculpt::detail::openProgram = {};  // what was not run is dropped with its buffers
    for (Graph& g : slots_)
      if (g.exec) cudaGraphExecDestroy(g.exec);
    for (auto& [flag, l] : loops_) {
      if (l.exec) cudaGraphExecDestroy(l.exec);
      if (l.passes) cudaFree(l.passes);
    }
    if (workspace_) cudaFree(workspace_);
    cudaFree(info_);
    cudaFree(partial_);
  }
  CudaExecutor(const CudaExecutor&) = delete;
  CudaExecutor& operator=(const CudaExecutor&) = delete;

  // What a frame costs the device (solver/frame/device_counters.h); the kernels of a replayed
  // graph are those counted when it was recorded.
  using Counters = DeviceCounters;
  Counters counters() const {
    countLoopPasses();
    if (programs_) {
      flush();
      counters_.barriers += runner_.barriersPassed();
    }
    Counters c = counters_;
    c.hostToDeviceBytes = ::galsculpt::detail::transfers.hostToDevice;
    c.deviceToHostBytes = ::galsculpt::detail::transfers.deviceToHost + readBytes_;
    return c;
  }

  // Whether launches are recorded into device programs (else each is a kernel).
  bool runsPrograms() const { return programs_; }

  template <typename F>
  void forEach(int n, const F& f, long /*cost: a CPU's threading hint*/ = 1) const {
    if (n <= 0) return;
    ++counters_.launches;
    if (programs_) {
      record().forEach(n, f);
      return;
    }
    ++counters_.programs;
    if (profile_) profile_->begin(GALSCULPT_CUDA_STREAM);
    forEachKernel<<<(n + kThreads - 1) / kThreads, kThreads, 0, GALSCULPT_CUDA_STREAM>>>(n, f);
    GALSCULPT_CUDA_CHECK(cudaGetLastError());
    if (profile_) profile_->end(GALSCULPT_CUDA_STREAM, "launch", typeid(F).name(), n);
  }
  template <typename F>
  void sum(int n, const F& f, double* out) const {
    reduce(n, f, AddOp{}, 0.0, out);
  }
  template <typename F>
  void maximum(int n, const F& f, double* out) const {
    reduce(n, f, MaxOp{}, -std::numeric_limits<double>::infinity(), out);
  }
  template <typename T>
  void copy(T* dst, const T* src, size_t n) const {
    if (!n) return;
    ++counters_.copies;
    if (programs_) {
      record().copy(dst, src, n * sizeof(T));
      return;
    }
    ++counters_.programs;
    GALSCULPT_CUDA_CHECK(
        cudaMemcpyAsync(dst, src, n * sizeof(T), cudaMemcpyDeviceToDevice, GALSCULPT_CUDA_STREAM));
  }
  template <typename T>
  void read(const T* deviceValues, T* host, int n) const {
    ++counters_.reads;
    download(deviceValues, host, static_cast<size_t>(n));
  }
  // Device to host through the pinned staging buffer (one DMA, one wait, one memcpy).
  template <typename T>
  void download(const T* device, T* host, size_t n) const {
    if (!n) return;
    flush();
    ++counters_.waits;
    readBytes_ += static_cast<double>(n * sizeof(T));
    void* pinned = staging_.get(n * sizeof(T));
    GALSCULPT_CUDA_CHECK(cudaMemcpyAsync(pinned, device, n * sizeof(T), cudaMemcpyDeviceToHost,
                                         GALSCULPT_CUDA_STREAM));
    GALSCULPT_CUDA_CHECK(cudaStreamSynchronize(GALSCULPT_CUDA_STREAM));
    std::memcpy(static_cast<void*>(host), pinned, n * sizeof(T));
  }
  // Several arrays device to host: queued into one pinned staging buffer, one wait, then copied
  // out (a frame's positions and velocities).
  void downloadAll(std::initializer_list<DownloadSpan> spans) const {
    size_t total = 0;
    for (const DownloadSpan& s : spans) total += s.bytes;
    if (!total) return;
    flush();
    ++counters_.waits;
    readBytes_ += static_cast<double>(total);
    char* pinned = static_cast<char*>(staging_.get(total));
    size_t at = 0;
    for (const DownloadSpan& s : spans) {
      if (s.bytes)
        GALSCULPT_CUDA_CHECK(cudaMemcpyAsync(pinned + at, s.device, s.bytes, cudaMemcpyDeviceToHost,
                                             GALSCULPT_CUDA_STREAM));
      at += s.bytes;
    }
    GALSCULPT_CUDA_CHECK(cudaStreamSynchronize(GALSCULPT_CUDA_STREAM));
    at = 0;
    for (const DownloadSpan& s : spans) {
      if (s.bytes) std::memcpy(s.host, pinned + at, s.bytes);
      at += s.bytes;
    }
  }
  // In-place dense Cholesky through cuSOLVER (loaded on first use), queued without a wait: its
  // status goes to *failed (device memory; 1 where the matrix is not positive definite), where
  // the frame's next read brings it. False when cuSOLVER is not there (cusolverReason() says
  // why).
  bool denseCholesky(int n, double* a, double* failed) {
    flush();
    if (!cusolver_.load(GALSCULPT_CUDA_STREAM, cusolverReason_)) return false;
    int lwork = 0;
    GALSCULPT_CUSOLVER_CHECK(cusolver_.bufferSize(n, a, &lwork));
    if (static_cast<size_t>(lwork) > workspaceSize_) {
      if (workspace_) GALSCULPT_CUDA_CHECK(cudaFree(workspace_));
      GALSCULPT_CUDA_CHECK(cudaMalloc(&workspace_, lwork * sizeof(double)));
      workspaceSize_ = lwork;
    }
    GALSCULPT_CUSOLVER_CHECK(cusolver_.potrf(n, a, workspace_, lwork, info_));
    ++counters_.programs;  // a library's call, counted as one kernel (it launches a few)
    const int* info = info_;
    forEach(1, [=] __device__(int) { *failed = *info != 0 ? 1.0 : 0.0; });
    return true;
  }
  // inverse = (L Lᵀ)⁻¹ from denseCholesky's factor: cuSOLVER's solve on the identity, queued
  // after the program open (which it ends), with no wait.
  void denseCholeskyInverse(int n, const double* l, double* inverse) {
    flush();
    forEach(n * n, [=] __device__(int e) { inverse[e] = e % (n + 1) == 0 ? 1.0 : 0.0; });
    flush();
    GALSCULPT_CUSOLVER_CHECK(cusolver_.potrs(n, n, l, inverse, info_));
    ++counters_.programs;
  }
  const std::string& cusolverReason() const { return cusolverReason_; }
  // Runs `body` (launches only, no host reads) as a CUDA graph: recorded on first use or when
  // the key changes, replayed otherwise. GALSCULPT_CUDA_GRAPHS=0 runs it directly.
  template <typename Body>
  void captured(int slot, std::uint64_t key, const Body& body) {
    if (programs_ || !graphs_) {  // a program records the section with the launches around it
      body();
      return;
    }
    if (slot >= static_cast<int>(slots_.size())) slots_.resize(slot + 1);
    Graph& g = slots_[slot];
    if (!g.exec || g.key != key) {
      const Counters before = counters_;
      if (g.exec) GALSCULPT_CUDA_CHECK(cudaGraphExecDestroy(g.exec));
      g.exec = nullptr;
      cudaGraph_t graph = nullptr;
      GALSCULPT_CUDA_CHECK(
          cudaStreamBeginCapture(GALSCULPT_CUDA_STREAM, cudaStreamCaptureModeThreadLocal));
      try {
        body();
      } catch (...) {
        cudaStreamEndCapture(GALSCULPT_CUDA_STREAM, &graph);
        if (graph) cudaGraphDestroy(graph);
        throw;
      }
      GALSCULPT_CUDA_CHECK(cudaStreamEndCapture(GALSCULPT_CUDA_STREAM, &graph));
      GALSCULPT_CUDA_CHECK(cudaGraphInstantiate(&g.exec, graph, 0));
      GALSCULPT_CUDA_CHECK(cudaGraphDestroy(graph));
      g.key = key;
      g.launches = counters_.launches - before.launches;
      g.reductions = counters_.reductions - before.reductions;
      g.copies = counters_.copies - before.copies;
      g.programs = counters_.programs - before.programs;
    } else {  // the recorded kernels run again
      counters_.launches += g.launches;
      counters_.reductions += g.reductions;
      counters_.copies += g.copies;
      counters_.programs += g.programs;
    }
    ++counters_.graphs;
    GALSCULPT_CUDA_CHECK(cudaGraphLaunch(g.exec, GALSCULPT_CUDA_STREAM));
  }
  // `body` (launches only) while *running is not 0, tested on the device before each pass, at
  // most `mostPasses` passes: a graph of the test and a while node whose body graph is `body`'s
  // launches and the test again (CUDA 12.4's conditional nodes), recorded once per flag and key
  // and replayed. The host waits for nothing. Without graphs (GALSCULPT_CUDA_GRAPHS=0, the
  // launch profile) the host reads the flag before each pass.
  template <typename Body>
  void loopOnDevice(std::uint64_t key, const double* running, int mostPasses,
                    const Body& body) const {
    if (programs_) {
      const int entry = record().loopEntry(running, mostPasses);
      body();
      record().loopTest(entry);
      return;
    }
#if CUDART_VERSION >= 12040
    if (graphs_) {
      Loop& l = loops_[running];
      if (!l.exec || l.key != key) recordLoop(l, key, running, mostPasses, body);
      ++counters_.graphs;
      ++counters_.programs;  // the entry's test (the passes are counted by countLoopPasses)
      GALSCULPT_CUDA_CHECK(cudaGraphLaunch(l.exec, GALSCULPT_CUDA_STREAM));
      return;
    }
#endif
    for (int pass = 0; pass < mostPasses; ++pass) {
      double flag = 0.0;
      read(running, &flag, 1);
      if (flag == 0.0) break;
      body();
    }
  }
  void synchronize() const {
    flush();
    GALSCULPT_CUDA_CHECK(cudaStreamSynchronize(GALSCULPT_CUDA_STREAM));
  }
  // Runs the program open, if any, without waiting for it.
  void flush() const {
    if (::galsculpt::detail::openProgram.executor == this) ::galsculpt::detail::closeOpenProgram();
  }

 private:
  template <typename F, typename Op>
  void reduce(int n, const F& f, Op op, double identity, double* out) const {
    const int blocks = n <= 0 ? 1 : std::min(kReduceBlocks, (n + kThreads - 1) / kThreads);
    ++counters_.reductions;
    if (programs_) {
      record().template reduce<F, Op>(n, f, identity, partial_, out);
      return;
    }
    counters_.programs += 2;
    if (profile_) profile_->begin(GALSCULPT_CUDA_STREAM);
    reduceKernel<<<blocks, kThreads, 0, GALSCULPT_CUDA_STREAM>>>(n, f, op, identity, partial_);
    GALSCULPT_CUDA_CHECK(cudaGetLastError());
    finishKernel<<<1, kThreads, 0, GALSCULPT_CUDA_STREAM>>>(blocks, partial_, op, identity, out);
    GALSCULPT_CUDA_CHECK(cudaGetLastError());
    if (profile_) profile_->end(GALSCULPT_CUDA_STREAM, "reduce", typeid(F).name(), n);
  }
  struct Graph {
    std::uint64_t key = 0;
    cudaGraphExec_t exec = nullptr;
    long launches = 0, reductions = 0, copies = 0, programs = 0;  // the kernels it holds
  };
  // A device loop's graph: the kernels of one pass, and its pass counter (device memory: the
  // passes made, and where the last launch started) with the passes counters() has counted.
  struct Loop {
    std::uint64_t key = 0;
    cudaGraphExec_t exec = nullptr;
    long launches = 0, reductions = 0, copies = 0, programs = 0;  // a pass's (its test too)
    long long* passes = nullptr;
    long long counted = 0;
  };
#if CUDART_VERSION >= 12040
  template <typename Body>
  void recordLoop(Loop& l, std::uint64_t key, const double* running, int mostPasses,
                  const Body& body) const {
    if (l.exec) GALSCULPT_CUDA_CHECK(cudaGraphExecDestroy(l.exec));
    l.exec = nullptr;
    if (!l.passes) {
      GALSCULPT_CUDA_CHECK(cudaMalloc(&l.passes, 2 * sizeof(long long)));
      GALSCULPT_CUDA_CHECK(
          cudaMemsetAsync(l.passes, 0, 2 * sizeof(long long), GALSCULPT_CUDA_STREAM));
      l.counted = 0;
    }
    cudaGraph_t graph = nullptr;
    GALSCULPT_CUDA_CHECK(cudaGraphCreate(&graph, 0));
    try {
      cudaGraphConditionalHandle handle;
      GALSCULPT_CUDA_CHECK(cudaGraphConditionalHandleCreate(&handle, graph, 0, 0));
      long long* passes = l.passes;
      void* entryArgs[] = {&handle, const_cast<double**>(&running), &passes};
      cudaKernelNodeParams entry{};
      entry.func = reinterpret_cast<void*>(loopEntryKernel);
      entry.gridDim = dim3(1);
      entry.blockDim = dim3(1);
      entry.kernelParams = entryArgs;
      cudaGraphNode_t entryNode = nullptr;
      GALSCULPT_CUDA_CHECK(cudaGraphAddKernelNode(&entryNode, graph, nullptr, 0, &entry));
      cudaGraphNodeParams loop{};
      loop.type = cudaGraphNodeTypeConditional;
      loop.conditional.handle = handle;
      loop.conditional.type = cudaGraphCondTypeWhile;
      loop.conditional.size = 1;
      cudaGraphNode_t loopNode = nullptr;
#if CUDART_VERSION >= 13000
      GALSCULPT_CUDA_CHECK(cudaGraphAddNode(&loopNode, graph, &entryNode, nullptr, 1, &loop));
#else
      GALSCULPT_CUDA_CHECK(cudaGraphAddNode(&loopNode, graph, &entryNode, 1, &loop));
#endif
      cudaGraph_t bodyGraph = loop.conditional.phGraph_out[0];
      const Counters before = counters_;
      GALSCULPT_CUDA_CHECK(cudaStreamBeginCaptureToGraph(
          GALSCULPT_CUDA_STREAM, bodyGraph, nullptr, nullptr, 0, cudaStreamCaptureModeThreadLocal));
      try {
        body();
        loopTestKernel<<<1, 1, 0, GALSCULPT_CUDA_STREAM>>>(handle, running, passes, mostPasses);
        GALSCULPT_CUDA_CHECK(cudaGetLastError());
      } catch (...) {
        cudaStreamEndCapture(GALSCULPT_CUDA_STREAM, &bodyGraph);
        throw;
      }
      GALSCULPT_CUDA_CHECK(cudaStreamEndCapture(GALSCULPT_CUDA_STREAM, &bodyGraph));
      // The capture launched nothing: the passes are counted as they are made (counters()).
      l.launches = counters_.launches - before.launches;
      l.reductions = counters_.reductions - before.reductions;
      l.copies = counters_.copies - before.copies;
      l.programs = counters_.programs - before.programs + 1;  // and the test
      counters_ = before;
      GALSCULPT_CUDA_CHECK(cudaGraphInstantiate(&l.exec, graph, 0));
    } catch (...) {
      cudaGraphDestroy(graph);
      throw;
    }
    GALSCULPT_CUDA_CHECK(cudaGraphDestroy(graph));
    l.key = key;
  }
#endif
  // Adds the kernels of the loops' passes made since the last call (a download per loop: the
  // counters are read between frames, where the host waits anyway; not counted as a wait).
  void countLoopPasses() const {
    for (auto& [flag, l] : loops_) {
      if (!l.passes) continue;
      long long passes = 0;
      GALSCULPT_CUDA_CHECK(cudaMemcpyAsync(&passes, l.passes, sizeof passes, cudaMemcpyDeviceToHost,
                                           GALSCULPT_CUDA_STREAM));
      GALSCULPT_CUDA_CHECK(cudaStreamSynchronize(GALSCULPT_CUDA_STREAM));
      const long long made = passes - l.counted;
      l.counted = passes;
      counters_.launches += static_cast<long>(made) * l.launches;
      counters_.programs += static_cast<long>(made) * l.programs;
      counters_.reductions += static_cast<long>(made) * l.reductions;
      counters_.copies += static_cast<long>(made) * l.copies;
    }
  }
  // The program being recorded: opened by the first launch after a synchronization.
  ProgramRecorder& record() const {
    if (::galsculpt::detail::openProgram.executor != this) {
      ::galsculpt::detail::closeOpenProgram();
      // Launches left open on another thread (the step backend flushes each frame) run first.
      if (runner_.run()) ++counters_.programs;
      ::galsculpt::detail::openProgram = {[](void* executor) {
                                            const auto* ex =
                                                static_cast<const CudaExecutor*>(executor);
                                            if (ex->runner_.run()) ++ex->counters_.programs;
                                          },
                                          const_cast<CudaExecutor*>(this)};
    }
    return runner_.recorder();
  }
  bool programs_ = false;
  mutable ProgramRunner runner_;

  double* partial_ = nullptr;
  CusolverLibrary cusolver_;
  std::string cusolverReason_;
  int* info_ = nullptr;
  double* workspace_ = nullptr;
  size_t workspaceSize_ = 0;
  bool graphs_ = true;
  std::unique_ptr<LaunchProfile> profile_;  // GALSCULPT_CUDA_PROFILE=1
  mutable PinnedStaging staging_;
  mutable Counters counters_;
  mutable double readBytes_ = 0.0;  // host reads and downloads
  std::vector<Graph> slots_;
  mutable std::map<const double*, Loop> loops_;  // by the flag each tests
};

}  // namespace galsculpt::gpu

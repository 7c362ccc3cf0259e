// A device program: the launches a frame makes between two host synchronizations, run as one
// cooperative kernel (runDeviceProgram, device_program.cu) whose phases meet at grid-wide
// barriers. A phase is a forEach, a reduction's pass over its items or over its blocks, a copy,
// or a device loop's test; the host records them (ProgramRecorder) with each lambda's closure
// and the address of the device function that runs it, and the kernel steps through them. A GPU
// then pays one launch where it paid a kernel per launch, and a barrier (a few µs at most, with
// the grid sized to the largest phase) per phase. Loops whose test the device makes
// (CudaExecutor::loopOnDevice) are a jump back in the same kernel.
//
// The phases' functions are called through pointers, so the library is compiled for separable
// device code (gpu/CMakeLists.txt): a pointer taken in one translation unit is called from the
// kernel of another.
#pragma once

#include <cuda_runtime.h>

#include <algorithm>
#include <cstring>
#include <type_traits>
#include <vector>

namespace galsculpt::gpu {

inline constexpr int kThreads = 256;
inline constexpr int kReduceBlocks = 1024;
// A device program's stack a thread (ProgramRunner::start): the largest phase's frame and the
// kernel's own, with room (the device reserves it for every thread it can hold: 8 KB is about
// 2 GB on an H100).
inline constexpr size_t kProgramStackBytes = 8192;

struct AddOp {
  __host__ __device__ double operator()(double a, double b) const { return a + b; }
};
struct MaxOp {
  __host__ __device__ double operator()(double a, double b) const { return a > b ? a : b; }
};

// A block's threads combine their values in a fixed tree in `shared` (kThreads doubles); every
// thread gets the result.
template <typename Op>
__device__ double blockReduceIn(double* shared, double acc, Op op) {
  shared[threadIdx.x] = acc;
  __syncthreads();
  for (int stride = blockDim.x / 2; stride > 0; stride /= 2) {
    if (threadIdx.x < stride)
      shared[threadIdx.x] = op(shared[threadIdx.x], shared[threadIdx.x + stride]);
    __syncthreads();
  }
  const double total = shared[0];
  __syncthreads();  // before the next reduction writes `shared`
  return total;
}

struct ProgramOp;
using PhaseFunction = void (*)(const unsigned char* closure, const ProgramOp& op);

enum ProgramOpKind : int {
  kPhaseOp,      // fn over the items (a forEach, or a reduction's pass into `partial`)
  kFinishAddOp,  // one block adds `partial`'s blocks into *out
  kFinishMaxOp,  // one block takes their maximum
  kCopyOp,       // n bytes from src to dst
  kLoopEntryOp,  // on to `jump` (past the loop) unless *running is not 0
  kLoopTestOp,   // back to `jump` (the body's first op) while *running and passes < mostPasses
};

struct ProgramOp {
  int kind = kPhaseOp;
  int n = 0;             // items; bytes for a copy
  int blocks = 0;        // a reduction's blocks (the unfused kernel's grid, for its bits)
  int jump = 0;          // a loop's other end
  int mostPasses = 0;    // a loop's cap
  unsigned closure = 0;  // the closure's offset in the program's bytes
  PhaseFunction fn = nullptr;
  double identity = 0.0;  // a reduction's
  double* partial = nullptr;
  double* out = nullptr;
  const double* running = nullptr;  // a loop's flag
  void* dst = nullptr;
  const void* src = nullptr;
};

// The program's kernel (device_program.cu): `ops` at the start of `program`, the closures after
// them; `barriers` counts the barriers it passes (CudaExecutor::counters()). Needs
// kThreads * sizeof(double) bytes of dynamic shared memory (the reductions').
__global__ void runDeviceProgram(const unsigned char* program, int count,
                                 unsigned long long* barriers);

template <typename F>
__device__ void forEachPhase(const unsigned char* closure, const ProgramOp& op) {
  const F& f = *reinterpret_cast<const F*>(closure);
  for (int i = blockIdx.x * blockDim.x + threadIdx.x; i < op.n; i += gridDim.x * blockDim.x) f(i);
}

// The unfused reduction's first kernel (cuda_executor.cuh) with `op.blocks` blocks, each of the
// grid's blocks playing some of them: the same partition, the same tree, the same bits.
template <typename F, typename Op>
__device__ void reducePhase(const unsigned char* closure, const ProgramOp& op) {
  extern __shared__ double programShared[];
  const F& f = *reinterpret_cast<const F*>(closure);
  for (int b = blockIdx.x; b < op.blocks; b += gridDim.x) {
    double acc = op.identity;
    for (int i = b * blockDim.x + threadIdx.x; i < op.n; i += op.blocks * blockDim.x)
      acc = Op{}(acc, f(i));
    const double total = blockReduceIn(programShared, acc, Op{});
    if (threadIdx.x == 0) op.partial[b] = total;
  }
}

// Each phase function's device address, fetched once by a one-thread kernel (a device
// function's address is known only on the device).
template <typename F>
__global__ void forEachPhaseAddress(PhaseFunction* out) {
  *out = &forEachPhase<F>;
}
template <typename F, typename Op>
__global__ void reducePhaseAddress(PhaseFunction* out) {
  *out = &reducePhase<F, Op>;
}
// Runs `fetch` (one of the above) into a slot of device memory and reads it back (device.cu).
PhaseFunction fetchPhaseAddress(void (*fetch)(PhaseFunction*));
template <typename F>
PhaseFunction forEachPhasePointer() {
  static const PhaseFunction address = fetchPhaseAddress(&forEachPhaseAddress<F>);
  return address;
}
template <typename F, typename Op>
PhaseFunction reducePhasePointer() {
  static const PhaseFunction address = fetchPhaseAddress(&reducePhaseAddress<F, Op>);
  return address;
}

// The ops of the program being recorded and their closures' bytes, and the grid it needs.
class ProgramRecorder {
 public:
  bool empty() const { return ops_.empty(); }
  int size() const { return static_cast<int>(ops_.size()); }
  // The blocks its largest phase would have as a kernel of its own.
  int blocksWanted() const { return blocks_; }

  template <typename F>
  void forEach(int n, const F& f) {
    // A closure is copied as bytes, as a kernel's argument is (a host-device lambda's wrapper
    // is not trivially copyable in C++'s terms, and is passed to kernels so).
    ProgramOp op;
    op.n = n;
    op.fn = forEachPhasePointer<F>();
    op.closure = store(&f, sizeof(F));
    want((n + kThreads - 1) / kThreads);
    ops_.push_back(op);
  }
  template <typename F, typename Op>
  void reduce(int n, const F& f, double identity, double* partial, double* out) {
    ProgramOp pass;
    pass.n = n;
    pass.blocks = n <= 0 ? 1 : std::min(kReduceBlocks, (n + kThreads - 1) / kThreads);
    pass.identity = identity;
    pass.partial = partial;
    pass.fn = reducePhasePointer<F, Op>();
    pass.closure = store(&f, sizeof(F));
    want(pass.blocks);
    ops_.push_back(pass);
    ProgramOp finish = pass;
    finish.kind = std::is_same_v<Op, MaxOp> ? kFinishMaxOp : kFinishAddOp;
    finish.fn = nullptr;
    finish.out = out;
    ops_.push_back(finish);
  }
  void copy(void* dst, const void* src, size_t bytes) {
    ProgramOp op;
    op.kind = kCopyOp;
    op.n = static_cast<int>(bytes);
    op.dst = dst;
    op.src = src;
    want(static_cast<int>((bytes / 8 + kThreads - 1) / kThreads));
    ops_.push_back(op);
  }
  // A loop: its entry, the body's ops (recorded next), then loopTest(entry).
  int loopEntry(const double* running, int mostPasses) {
    ProgramOp op;
    op.kind = kLoopEntryOp;
    op.running = running;
    op.mostPasses = mostPasses;
    ops_.push_back(op);
    return size() - 1;
  }
  void loopTest(int entry) {
    ProgramOp op = ops_[entry];
    op.kind = kLoopTestOp;
    op.jump = entry + 1;
    ops_.push_back(op);
    ops_[entry].jump = size();
  }

  // The program's bytes: the ops, then the closures (offsets rebased past the ops).
  size_t bytes() const { return opsBytes() + closures_.size(); }
  void write(unsigned char* to) const {
    const size_t base = opsBytes();
    for (size_t k = 0; k < ops_.size(); ++k) {
      ProgramOp op = ops_[k];
      op.closure += static_cast<unsigned>(base);
      std::memcpy(to + k * sizeof(ProgramOp), &op, sizeof op);
    }
    if (!closures_.empty()) std::memcpy(to + base, closures_.data(), closures_.size());
  }
  void clear() {
    ops_.clear();
    closures_.clear();
    blocks_ = 1;
  }

 private:
  static constexpr size_t kAlign = 16;
  size_t opsBytes() const {
    return (ops_.size() * sizeof(ProgramOp) + kAlign - 1) / kAlign * kAlign;
  }
  unsigned store(const void* closure, size_t size) {
    const size_t at = (closures_.size() + kAlign - 1) / kAlign * kAlign;
    closures_.resize(at + size);
    std::memcpy(closures_.data() + at, closure, size);
    return static_cast<unsigned>(at);
  }
  void want(int blocks) { blocks_ = std::max(blocks_, blocks); }

  std::vector<ProgramOp> ops_;
  std::vector<unsigned char> closures_;
  int blocks_ = 1;
};

// Runs recorded programs: each uploaded through one of four pinned slots (whose last upload is
// long done: a wait comes between most programs) and launched cooperatively, on as many blocks
// as its largest phase has, at most as many as can be resident.
class ProgramRunner {
 public:
  ProgramRunner() = default;
  ProgramRunner(const ProgramRunner&) = delete;
  ProgramRunner& operator=(const ProgramRunner&) = delete;
  ~ProgramRunner();
  // Whether this GPU runs programs: it launches cooperatively, and the kernel fits a block on
  // each multiprocessor at least.
  bool start();
  ProgramRecorder& recorder() { return recorder_; }
  // Launches what was recorded, and clears it; false when there was nothing.
  bool run();
  // The barriers the programs passed since the last call (a wait: read between frames).
  long barriersPassed();

 private:
  struct Slot {
    void* pinned = nullptr;
    unsigned char* device = nullptr;
    size_t bytes = 0;
    cudaEvent_t done = nullptr;
  };
  ProgramRecorder recorder_;
  std::vector<Slot> slots_ = std::vector<Slot>(4);
  size_t next_ = 0;
  int residentBlocks_ = 0;
  unsigned long long* barriers_ = nullptr;  // device memory
  unsigned long long counted_ = 0;
};

}  // namespace galsculpt::gpu

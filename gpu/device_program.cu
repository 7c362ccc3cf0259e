// The device program's kernel (device_program.cuh): every block steps through the same ops,
// each op ends at a grid-wide barrier, and a loop's test is read by every thread between two
// barriers (the op before it wrote the flag; none after it writes it before all have read).
#include <cooperative_groups.h>

#include "gpu/cuda_check.h"
#include "gpu/device_program.cuh"

namespace galsculpt::gpu {

namespace {

template <typename Op>
__device__ void finishBlocks(const ProgramOp& op, Op reduce) {
  extern __shared__ double programShared[];
  double acc = op.identity;
  for (int i = threadIdx.x; i < op.blocks; i += blockDim.x) acc = reduce(acc, op.partial[i]);
  const double total = blockReduceIn(programShared, acc, reduce);
  if (threadIdx.x == 0) *op.out = total;
}

__device__ void copyBytes(const ProgramOp& op) {
  const int stride = gridDim.x * blockDim.x;
  const int first = blockIdx.x * blockDim.x + threadIdx.x;
  const bool words = op.n % 8 == 0 && reinterpret_cast<size_t>(op.dst) % 8 == 0 &&
                     reinterpret_cast<size_t>(op.src) % 8 == 0;
  if (words) {
    auto* to = static_cast<unsigned long long*>(op.dst);
    const auto* from = static_cast<const unsigned long long*>(op.src);
    for (int i = first; i < op.n / 8; i += stride) to[i] = from[i];
  } else {
    auto* to = static_cast<unsigned char*>(op.dst);
    const auto* from = static_cast<const unsigned char*>(op.src);
    for (int i = first; i < op.n; i += stride) to[i] = from[i];
  }
}

__device__ bool flagSet(const double* running) {
  return *static_cast<const volatile double*>(running) != 0.0;
}

}  // namespace

__global__ void runDeviceProgram(const unsigned char* program, int count,
                                 unsigned long long* barriers) {
  cooperative_groups::grid_group grid = cooperative_groups::this_grid();
  const auto* ops = reinterpret_cast<const ProgramOp*>(program);
  const bool counts = blockIdx.x == 0 && threadIdx.x == 0;
  int pass = 0;  // of the loop under way (loops do not nest)
  for (int k = 0; k < count;) {
    const ProgramOp op = ops[k];
    int next = k + 1;
    switch (op.kind) {
      case kPhaseOp:
        op.fn(program + op.closure, op);
        break;
      case kFinishAddOp:
        if (blockIdx.x == 0) finishBlocks(op, AddOp{});
        break;
      case kFinishMaxOp:
        if (blockIdx.x == 0) finishBlocks(op, MaxOp{});
        break;
      case kCopyOp:
        copyBytes(op);
        break;
      case kLoopEntryOp:
        pass = 0;
        if (op.mostPasses <= 0 || !flagSet(op.running)) next = op.jump;
        break;
      case kLoopTestOp:
        ++pass;
        if (flagSet(op.running) && pass < op.mostPasses) next = op.jump;
        break;
      default:
        break;
    }
    if (counts) ++*barriers;
    grid.sync();
    k = next;
  }
}

PhaseFunction fetchPhaseAddress(void (*fetch)(PhaseFunction*)) {
  static PhaseFunction* slot = nullptr;
  if (!slot) GALSCULPT_CUDA_CHECK(cudaMalloc(&slot, sizeof(PhaseFunction)));
  void* args[] = {&slot};
  GALSCULPT_CUDA_CHECK(cudaLaunchKernel(reinterpret_cast<const void*>(fetch), dim3(1), dim3(1),
                                        args, 0, GALSCULPT_CUDA_STREAM));
  PhaseFunction address = nullptr;
  GALSCULPT_CUDA_CHECK(cudaMemcpyAsync(&address, slot, sizeof address, cudaMemcpyDeviceToHost,
                                       GALSCULPT_CUDA_STREAM));
  GALSCULPT_CUDA_CHECK(cudaStreamSynchronize(GALSCULPT_CUDA_STREAM));
  return address;
}

ProgramRunner::~ProgramRunner() {
  for (Slot& slot : slots_) {
    if (slot.done) cudaEventDestroy(slot.done);
    if (slot.device) cudaFree(slot.device);
    if (slot.pinned) cudaFreeHost(slot.pinned);
  }
  if (barriers_) cudaFree(barriers_);
}

bool ProgramRunner::start() {
  int device = 0, cooperative = 0, processors = 0, perProcessor = 0;
  if (cudaGetDevice(&device) != cudaSuccess ||
      cudaDeviceGetAttribute(&cooperative, cudaDevAttrCooperativeLaunch, device) != cudaSuccess ||
      cudaDeviceGetAttribute(&processors, cudaDevAttrMultiProcessorCount, device) != cudaSuccess ||
      cudaOccupancyMaxActiveBlocksPerMultiprocessor(&perProcessor, runDeviceProgram, kThreads,
                                                    kThreads * sizeof(double)) != cudaSuccess) {
    cudaGetLastError();  // cleared: the executor runs without programs
    return false;
  }
  if (!cooperative || perProcessor < 1) return false;
  // The phases are called through pointers, so the kernel's stack is not known when it is
  // linked, and a thread gets the device's default (1 KB): the limit must cover the largest
  // phase's frame (the element kernels' reach about 5 KB on sm_90, as a kernel of their own
  // they get it by themselves).
  if (cudaDeviceSetLimit(cudaLimitStackSize, kProgramStackBytes) != cudaSuccess) {
    cudaGetLastError();
    return false;
  }
  residentBlocks_ = processors * perProcessor;
  GALSCULPT_CUDA_CHECK(cudaMalloc(&barriers_, sizeof(unsigned long long)));
  GALSCULPT_CUDA_CHECK(cudaMemset(barriers_, 0, sizeof(unsigned long long)));
  return true;
}

bool ProgramRunner::run() {
  if (recorder_.empty()) return false;
  Slot& slot = slots_[next_++ % slots_.size()];
  if (slot.done) GALSCULPT_CUDA_CHECK(cudaEventSynchronize(slot.done));
  const size_t bytes = recorder_.bytes();
  if (bytes > slot.bytes) {
    if (slot.device) GALSCULPT_CUDA_CHECK(cudaFree(slot.device));
    if (slot.pinned) GALSCULPT_CUDA_CHECK(cudaFreeHost(slot.pinned));
    slot.device = nullptr;
    slot.pinned = nullptr;
    const size_t room = std::max<size_t>(bytes * 2, 64 * 1024);
    GALSCULPT_CUDA_CHECK(cudaMallocHost(&slot.pinned, room));
    GALSCULPT_CUDA_CHECK(cudaMalloc(&slot.device, room));
    slot.bytes = room;
  }
  if (!slot.done)
    GALSCULPT_CUDA_CHECK(cudaEventCreateWithFlags(&slot.done, cudaEventDisableTiming));
  recorder_.write(static_cast<unsigned char*>(slot.pinned));
  GALSCULPT_CUDA_CHECK(cudaMemcpyAsync(slot.device, slot.pinned, bytes, cudaMemcpyHostToDevice,
                                       GALSCULPT_CUDA_STREAM));
  const unsigned char* program = slot.device;
  int count = recorder_.size();
  unsigned long long* barriers = barriers_;
  void* args[] = {&program, &count, &barriers};
  const int blocks = std::max(1, std::min(residentBlocks_, recorder_.blocksWanted()));
  recorder_.clear();
  GALSCULPT_CUDA_CHECK(cudaLaunchCooperativeKernel(
      reinterpret_cast<const void*>(runDeviceProgram), dim3(blocks), dim3(kThreads), args,
      kThreads * sizeof(double), GALSCULPT_CUDA_STREAM));
  GALSCULPT_CUDA_CHECK(cudaEventRecord(slot.done, GALSCULPT_CUDA_STREAM));
  return true;
}

long ProgramRunner::barriersPassed() {
  if (!barriers_) return 0;
  unsigned long long passed = 0;
  GALSCULPT_CUDA_CHECK(cudaMemcpyAsync(&passed, barriers_, sizeof passed, cudaMemcpyDeviceToHost,
                                       GALSCULPT_CUDA_STREAM));
  GALSCULPT_CUDA_CHECK(cudaStreamSynchronize(GALSCULPT_CUDA_STREAM));
  const long made = static_cast<long>(passed - counted_);
  counted_ = passed;
  return made;
}

}  // namespace galsculpt::gpu

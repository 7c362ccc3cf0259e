#include "gpu/executor_check.h"

#include <cmath>
#include <vector>

#include "gpu/cuda_executor.cuh"
#include "gpu/device_info.h"
#include "solver/fem/dense_kernels.h"

namespace galsculpt::gpu {

namespace {

// Runs `body(check)` where a GPU is usable; the check says why it did not run otherwise (no
// usable GPU, a CUDA error).
template <typename Check, typename Body>
Check runOnDevice(const Body& body) {
  Check check;
  const DeviceInfo info = queryDevice();
  if (!info.available) {
    check.reason = info.reason;
    return check;
  }
  try {
    body(check);
    check.ran = true;
  } catch (const std::exception& e) {
    check.reason = e.what();
  }
  return check;
}

}  // namespace

LoopCheck checkDeviceLoop(int stopAt, int mostPasses, bool startRunning, bool programs) {
  return runOnDevice<LoopCheck>([&](LoopCheck& check) {
    CudaExecutor ex(programs);
    check.programs = ex.runsPrograms();
    CudaExecutor::Buffer<double> state;  // the flag, the count
    state.upload(std::vector<double>{0.0, 0.0});
    double* s = state.data();
    const double start = startRunning ? 1.0 : 0.0, stop = stopAt;
    const DeviceCounters before = ex.counters();
    for (int launch = 0; launch < 2; ++launch) {
      ex.forEach(1, [=] GALSCULPT_LAMBDA(int) {
        s[0] = start;
        s[1] = 0.0;
      });
      ex.loopOnDevice(1, s, mostPasses, [&] {
        ex.forEach(1, [=] GALSCULPT_LAMBDA(int) {
          s[1] += 1.0;
          if (s[1] >= stop) s[0] = 0.0;
        });
      });
    }
    double read[2] = {0.0, 0.0};
    ex.read(s, read, 2);
    const DeviceCounters after = ex.counters();
    check.lastPasses = read[1];
    check.kernels = after.kernels() - before.kernels();
    check.waits = after.waits - before.waits;
    check.graphs = after.graphs - before.graphs;
    check.barriers = after.barriers - before.barriers;
  });
}

namespace {

// Sizes around the block (256) and the reduction's grid (1024 blocks) edges, a copy, and a loop
// whose passes reduce and decide from the sums.
std::vector<double> runProgramLaunches(CudaExecutor& ex, long& kernels, long& barriers) {
  const int sizes[] = {1, 255, 257, 70000, 300000};
  const int most = sizes[4];
  CudaExecutor::Buffer<double> items, copied, out;
  items.resize(most);
  copied.resize(most);
  out.resize(4 * 5 + 3);
  double* v = items.data();
  double* c = copied.data();
  double* o = out.data();
  const DeviceCounters before = ex.counters();
  ex.forEach(most, [=] GALSCULPT_LAMBDA(int i) { v[i] = sin(0.001 * i) + 1e-3 * (i % 7); });
  for (int k = 0; k < 5; ++k) {
    const int n = sizes[k];
    ex.sum(
        n, [=] GALSCULPT_LAMBDA(int i) { return v[i] * v[i]; }, o + 4 * k);
    ex.maximum(
        n, [=] GALSCULPT_LAMBDA(int i) { return v[i]; }, o + 4 * k + 1);
    ex.sum(
        n, [=] GALSCULPT_LAMBDA(int i) { return 1.0 / (1.0 + v[i] * v[i]); }, o + 4 * k + 2);
  }
  ex.copy(c, v, most);
  ex.forEach(1, [=] GALSCULPT_LAMBDA(int) {
    o[20] = 1.0;  // running
    o[21] = 0.0;  // passes
    o[22] = 0.0;  // accumulated
  });
  ex.loopOnDevice(2, o + 20, 50, [&] {
    ex.sum(
        most, [=] GALSCULPT_LAMBDA(int i) { return c[i] * (o[21] + 1.0); }, o + 3);
    ex.forEach(1, [=] GALSCULPT_LAMBDA(int) {
      o[21] += 1.0;
      o[22] += o[3];
      if (o[21] >= 9.0) o[20] = 0.0;
    });
  });
  std::vector<double> result(out.size());
  ex.read(out.data(), result.data(), static_cast<int>(result.size()));
  const DeviceCounters after = ex.counters();
  kernels = after.kernels() - before.kernels();
  barriers = after.barriers - before.barriers;
  return result;
}

}  // namespace

ProgramCheck checkDeviceProgram() {
  return runOnDevice<ProgramCheck>([](ProgramCheck& check) {
    long barriers = 0;
    CudaExecutor fused(true);
    check.programs = fused.runsPrograms();
    check.fused = runProgramLaunches(fused, check.fusedKernels, check.fusedBarriers);
    CudaExecutor separate(false);
    check.separate = runProgramLaunches(separate, check.separateKernels, barriers);
  });
}

}  // namespace galsculpt::gpu

#include "gpu/executor_check.h"

#include <vector>

#include "gpu/cuda_executor.cuh"
#include "gpu/device_info.h"
#include "solver/fem/dense_kernels.h"

namespace galsculpt::gpu {

LoopCheck checkDeviceLoop(int stopAt, int mostPasses, bool startRunning) {
  LoopCheck check;
  const DeviceInfo info = queryDevice();
  if (!info.available) {
    check.reason = info.reason;
    return check;
  }
  try {
    CudaExecutor ex;
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
    check.ran = true;
  } catch (const std::exception& e) {
    check.reason = e.what();
  }
  return check;
}

}  // namespace galsculpt::gpu

// Checks of the CUDA executor's own machinery on the device, for gpu_tests (plain C++: callers
// need no CUDA headers).
#pragma once

#include <string>
#include <vector>

namespace galsculpt::gpu {

// A device loop (CudaExecutor::loopOnDevice) launched twice (with programs off: recorded as a
// graph, then replayed): each launch starts its flag at `startRunning` and a count at 0; each
// pass adds 1 to the count and clears the flag once the count reaches `stopAt`; at most
// `mostPasses` passes. `programs`: the executor records device programs (where the GPU can).
struct LoopCheck {
  bool ran = false;
  std::string reason;       // why it did not run (no usable GPU, a CUDA error)
  bool programs = false;    // whether the executor ran device programs
  double lastPasses = 0.0;  // the count after the second launch
  long kernels = 0, waits = 0, graphs = 0, barriers = 0;  // over both launches and the read
};
LoopCheck checkDeviceLoop(int stopAt, int mostPasses, bool startRunning = true,
                          bool programs = false);

// One program's worth of launches (a forEach, sums and maxima over a few sizes, a copy, a loop
// of reductions) run with device programs and without: what each gives, to compare bit for bit.
struct ProgramCheck {
  bool ran = false;
  std::string reason;
  bool programs = false;                // whether the first run ran as device programs
  std::vector<double> fused, separate;  // the results
  long fusedKernels = 0, separateKernels = 0, fusedBarriers = 0;
};
ProgramCheck checkDeviceProgram();

}  // namespace galsculpt::gpu

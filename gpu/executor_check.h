// Checks of the CUDA executor's own machinery on the device, for gpu_tests (plain C++: callers
// need no CUDA headers).
#pragma once

#include <string>

namespace galsculpt::gpu {

// A device loop (CudaExecutor::loopOnDevice) launched twice (recorded, then replayed): each
// launch starts its flag at `startRunning` and a count at 0; each pass adds 1 to the count and
// clears the flag once the count reaches `stopAt`; at most `mostPasses` passes.
struct LoopCheck {
  bool ran = false;
  std::string reason;                       // why it did not run (no usable GPU, a CUDA error)
  double lastPasses = 0.0;                  // the count after the second launch
  long kernels = 0, waits = 0, graphs = 0;  // counted over both launches and the read
};
LoopCheck checkDeviceLoop(int stopAt, int mostPasses, bool startRunning = true);

}  // namespace galsculpt::gpu

// The CPU executor with the CUDA executor's memory model: kHostMemory false, so the frame takes
// every path it takes on a GPU (no SIMD lanes, no host-only solvers or kept coarse factors, the
// elements evaluated where the host copies them) while running on the CPU. What differs between
// this and the CUDA backend is then the GPU's own (arithmetic order, launches, graphs); what
// differs between this and the CPU backend is the frame's device paths. Its counters
// (CpuExecutor::Counters) are then what the device pays a frame: `bench --backend device-like`
// reports them on any machine.
#pragma once

#include "solver/frame/cpu_executor.h"

namespace galsculpt {

class DeviceLikeExecutor : public CpuExecutor {
 public:
  static constexpr const char* kName = "device-like";
  static constexpr bool kHostMemory = false;
  // Serial and backwards: a launch whose items depend on each other's order shows here.
  template <typename F>
  void forEach(int n, const F& f, long = 1) const {
    countLaunch();
    for (int i = n - 1; i >= 0; --i) f(i);
  }
};

}  // namespace galsculpt

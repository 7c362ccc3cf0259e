// The key of a captured section (Exec::captured): a hash of everything the section bakes in,
// so that a CUDA graph is replayed only while none of it changed (sizes, device pointers,
// settings). FNV-1a over 64-bit words.
#pragma once

#include <cstdint>
#include <cstring>

#include "solver/frame/step.h"

namespace galsculpt {

class GraphKey {
 public:
  GraphKey& mix(std::uint64_t v) {
    key_ = (key_ ^ v) * 1099511628211ull;
    return *this;
  }
  GraphKey& mixDouble(double d) {
    std::uint64_t bits;
    std::memcpy(&bits, &d, sizeof bits);
    return mix(bits);
  }
  GraphKey& mixPointer(const void* p) { return mix(reinterpret_cast<std::uintptr_t>(p)); }
  // The step settings a captured Newton step or sub-step end reads.
  GraphKey& mixSettings(const StepSettings& s) {
    mix(static_cast<std::uint64_t>(s.newtonIterations));
    mix(static_cast<std::uint64_t>(s.fineSweeps));
    mix(static_cast<std::uint64_t>(s.coarseIterations) << 32 |
        static_cast<std::uint32_t>(s.cycles));
    mix(static_cast<std::uint64_t>(s.smoother));
    mixDouble(s.pcgTolerance);  // (under PCG the device's smoother: multigrid_cycle.h)
    mixDouble(s.stiffnessTolerance);
    return mix(s.reuseStiffness);  // the trial counts switched cracks only for chord steps
  }
  std::uint64_t value() const { return key_; }

 private:
  std::uint64_t key_ = 1469598103934665603ull;
};

}  // namespace galsculpt

// The key of a captured section (Exec::captured): LaunchKey (solver/fem/launch_key.h) with the
// step settings a captured Newton step or sub-step end reads.
#pragma once

#include <cstdint>

#include "solver/fem/launch_key.h"
#include "solver/frame/step.h"

namespace galsculpt {

class GraphKey {
 public:
  GraphKey& mix(std::uint64_t v) {
    key_.mix(v);
    return *this;
  }
  GraphKey& mixDouble(double d) {
    key_.mixDouble(d);
    return *this;
  }
  GraphKey& mixPointer(const void* p) {
    key_.mixPointer(p);
    return *this;
  }
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
  std::uint64_t value() const { return key_.value(); }

 private:
  LaunchKey key_;
};

}  // namespace galsculpt

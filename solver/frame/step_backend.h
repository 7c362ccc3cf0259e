// Where a frame is computed: the CPU executor (cpu_backend.h) or the CUDA one (gpu/). Both
// run the same frame loop (frame_loop.h) and the same element kernels (element_kernels.h), take
// the model and settings as they are, and leave the results in the caller's SimState, so the
// engine never knows which one ran.
#pragma once

#include <memory>
#include <string>

#include "solver/frame/step.h"

namespace galsculpt {

class StepBackend {
 public:
  virtual ~StepBackend() = default;
  virtual std::string name() const = 0;  // "cpu", "cuda" (for display)
  // Whether frames run elsewhere than on this CPU, so that a failure can fall back to it.
  virtual bool offloads() const = 0;
  // One frame of dt; the state is read at the start and written back at the end.
  virtual StepReport step(SimState& state, const StepSettings& settings) = 0;
  // What the solver carries from one frame to the next beyond the state: the coarsest matrix
  // whose factorization the multigrid keeps while its matrix stays close to it. Saved with a
  // state (Simulation::snapshot, projects) and adopted where the state is restored, so that a
  // reopened project or an undone action runs on to the same bits as the frames after the save.
  virtual std::vector<double> carriedState() const { return {}; }
  virtual void adoptCarriedState(std::vector<double>) {}
};

}  // namespace galsculpt

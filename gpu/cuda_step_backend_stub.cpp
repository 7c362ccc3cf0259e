// The CUDA backend's entry points in builds without nvcc: it is not there, and says so.
#include "gpu/cuda_step_backend.h"

#include "solver/frame/linear_solve.h"

namespace galsculpt::gpu {

bool cudaBackendBuilt() {
  return false;
}

std::unique_ptr<StepBackend> makeCudaStepBackend(const SimModel& model,
                                                 const StepSettings& settings,
                                                 std::string& reason) {
  reason = cudaUnsupportedReason(model, settings);
  if (reason.empty())
    reason = "this build has no CUDA backend (nvcc was not found when it was configured)";
  return nullptr;
}

}  // namespace galsculpt::gpu

#include "engine/session/backend_select.h"

#include "gpu/cuda_step_backend.h"
#include "solver/frame/device_like_backend.h"

namespace galsculpt {

BackendChoice chooseBackend(BackendRequest requested, const SimModel& model,
                            const StepSettings& settings) {
  BackendChoice choice;
  if (requested == BackendRequest::DeviceLike) {
    if (!settings.multigrid()) {
      choice.note = "the device-like backend runs the multigrid only: running on the CPU";
    } else {
      choice.backend = makeDeviceLikeStepBackend(model);
      return choice;
    }
  } else if (requested != BackendRequest::Cpu) {
    std::string reason;
    choice.backend = gpu::makeCudaStepBackend(model, settings, reason);
    if (choice.backend) return choice;
    if (requested == BackendRequest::Cuda)
      choice.note = "the CUDA backend is not available (" + reason + "): running on the CPU";
    else
      choice.fallback = "backend auto: (" + reason + "): running on the CPU";
  }
  choice.backend = std::make_unique<CpuStepBackend>(model);
  return choice;
}

}  // namespace galsculpt

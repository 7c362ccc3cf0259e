#include "gpu/cuda_executor.cuh"
#include "gpu/cuda_step_backend.h"
#include "gpu/device_info.h"
#include "solver/frame/executor_step_backend.h"

namespace galsculpt::gpu {

bool cudaBackendBuilt() {
  return true;
}

std::unique_ptr<StepBackend> makeCudaStepBackend(const SimModel& model,
                                                 const StepSettings& settings,
                                                 std::string& reason) {
  reason = cudaUnsupportedReason(model, settings);
  if (!reason.empty()) return nullptr;
  const DeviceInfo info = queryDevice();
  if (!info.available) {
    reason = info.reason;
    return nullptr;
  }
  if (info.computeMajor < 7 || (info.computeMajor == 7 && info.computeMinor < 5)) {
    reason = "GPU " + info.name + " (compute " + std::to_string(info.computeMajor) + "." +
             std::to_string(info.computeMinor) + ") is older than this build's sm_75";
    return nullptr;
  }
  try {
    return std::make_unique<ExecutorStepBackend<CudaExecutor>>(model);
  } catch (const std::exception& e) {
    reason = std::string("the CUDA backend could not start: ") + e.what();
    return nullptr;
  }
}

}  // namespace galsculpt::gpu

#include "cuda_executor.cuh"
#include "cuda_step_backend.h"
#include "device_info.h"
#include "device_solver.h"

namespace galsculpt::gpu {

namespace {

class CudaStepBackend final : public StepBackend {
 public:
  explicit CudaStepBackend(const SimModel& model) : solver_(executor_, model) {}
  std::string name() const override { return "cuda"; }
  // A CUDA error mid-frame throws before the state is written back: the caller may run the
  // frame again elsewhere.
  StepReport step(SimState& state, const StepSettings& settings) override {
    return solver_.step(state, settings);
  }

 private:
  CudaExecutor executor_;
  DeviceSolver<CudaExecutor> solver_;
};

}  // namespace

bool cudaBackendBuilt() {
  return true;
}

std::unique_ptr<StepBackend> makeCudaStepBackend(const SimModel& model,
                                                 const StepSettings& settings,
                                                 std::string& reason) {
  reason = deviceUnsupportedReason(settings);
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
    return std::make_unique<CudaStepBackend>(model);
  } catch (const std::exception& e) {
    reason = std::string("the CUDA backend could not start: ") + e.what();
    return nullptr;
  }
}

}  // namespace galsculpt::gpu

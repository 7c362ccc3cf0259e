#include "solver/frame/device_like_backend.h"

#include "solver/frame/device_like_executor.h"
#include "solver/frame/element_launches.h"
#include "solver/frame/executor_step_backend.h"

namespace galsculpt {

GALSCULPT_INSTANTIATE_ELEMENT_LAUNCHES(DeviceLikeExecutor);

std::unique_ptr<StepBackend> makeDeviceLikeStepBackend(const SimModel& model) {
  return std::make_unique<ExecutorStepBackend<DeviceLikeExecutor>>(model);
}

}  // namespace galsculpt

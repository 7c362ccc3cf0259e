// The device-like backend: the frame on the DeviceLikeExecutor (device_like_executor.h), the
// CUDA backend's paths run on the CPU, serially. Slow, but its launch, synchronization and
// transfer counts are the device's (StepReport::launches and the rows beside it), on any
// machine: `--backend device-like`.
#pragma once

#include <memory>

#include "solver/frame/step_backend.h"

namespace galsculpt {

std::unique_ptr<StepBackend> makeDeviceLikeStepBackend(const SimModel& model);

}  // namespace galsculpt

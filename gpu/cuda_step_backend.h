// The CUDA backend behind the solver's StepBackend interface. Plain C++: callers need no CUDA
// headers, and this header exists in builds without CUDA (cudaBackendBuilt() says false).
#pragma once

#include <memory>
#include <string>

#include "solver/frame/step_backend.h"

namespace galsculpt::gpu {

// Whether this build contains the CUDA backend (nvcc was found at configure time).
bool cudaBackendBuilt();

// The frame (solver/frame/frame_solver.h) on the CUDA executor of the first device, for `model`
// (which must outlive it). Returns null, with the reason in `reason`, when no usable device exists,
// the settings need something only the CPU has, or the device cannot hold the model. Never throws.
std::unique_ptr<StepBackend> makeCudaStepBackend(const SimModel& model,
                                                 const StepSettings& settings, std::string& reason);

}  // namespace galsculpt::gpu

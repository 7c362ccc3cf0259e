// The element launches (solver/frame/element_launches.h) for the CUDA executor: the one
// translation unit of the CUDA backend that includes a material model. Each launch is a host
// function that starts its own kernel, so the frame's translation unit calls it without
// separable compilation.
#include "gpu/cuda_executor.cuh"
#include "solver/frame/element_launches.h"

namespace galsculpt {

GALSCULPT_INSTANTIATE_ELEMENT_LAUNCHES(gpu::CudaExecutor);

}  // namespace galsculpt

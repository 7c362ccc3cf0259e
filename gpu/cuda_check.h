// CUDA and cuSOLVER calls, checked: a failure throws CudaError naming the call, file and line.
// And the stream everything runs on.
#pragma once

#include <cuda_runtime.h>
#include <cusolverDn.h>

#include <stdexcept>
#include <string>

namespace galsculpt::gpu {

class CudaError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

inline void checkCuda(cudaError_t status, const char* call, const char* file, int line) {
  if (status == cudaSuccess) return;
  throw CudaError(std::string(file) + ":" + std::to_string(line) + ": " + call + ": " +
                  cudaGetErrorString(status));
}
inline void checkCusolver(cusolverStatus_t status, const char* call, const char* file, int line) {
  if (status == CUSOLVER_STATUS_SUCCESS) return;
  throw CudaError(std::string(file) + ":" + std::to_string(line) + ": " + call +
                  ": cuSOLVER status " + std::to_string(static_cast<int>(status)));
}
#define GALSCULPT_CUDA_CHECK(call) ::galsculpt::gpu::checkCuda((call), #call, __FILE__, __LINE__)
#define GALSCULPT_CUSOLVER_CHECK(call) \
  ::galsculpt::gpu::checkCusolver((call), #call, __FILE__, __LINE__)

// The per-thread default stream: capturable, and no handle to pass around (a macro in the CUDA
// headers, hence one here).
#define GALSCULPT_CUDA_STREAM cudaStreamPerThread

}  // namespace galsculpt::gpu

#include <cuda_runtime.h>

#include "gpu/device_info.h"

namespace galsculpt::gpu {

DeviceInfo queryDevice() {
  DeviceInfo info;
  int count = 0;
  const cudaError_t status = cudaGetDeviceCount(&count);
  if (status != cudaSuccess) {
    info.reason = std::string("CUDA unavailable: ") + cudaGetErrorString(status);
    cudaGetLastError();  // clear the sticky error
    return info;
  }
  if (count == 0) {
    info.reason = "no CUDA device";
    return info;
  }
  cudaDeviceProp prop{};
  if (cudaGetDeviceProperties(&prop, 0) != cudaSuccess) {
    info.reason = "cannot query CUDA device 0";
    return info;
  }
  info.available = true;
  info.name = prop.name;
  info.computeMajor = prop.major;
  info.computeMinor = prop.minor;
  info.memoryBytes = prop.totalGlobalMem;
  return info;
}

}  // namespace galsculpt::gpu

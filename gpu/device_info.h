// What CUDA device, if any, this process can use. Plain C++: callers need no CUDA headers.
#pragma once

#include <string>

namespace galsculpt::gpu {

struct DeviceInfo {
  bool available = false;
  std::string name;  // e.g. "NVIDIA H100 80GB HBM3"
  int computeMajor = 0, computeMinor = 0;
  std::size_t memoryBytes = 0;
  std::string reason;  // why none is available ("no CUDA device", driver error text)
};

// Never throws: any CUDA error (no driver, no device) means "not available", with the reason.
DeviceInfo queryDevice();

}  // namespace galsculpt::gpu

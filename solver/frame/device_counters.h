// What a frame costs a device, counted by the executors (cpu_executor.h, and the CUDA one in
// gpu/cuda_executor.cuh): kernels, host waits, graph launches and bytes moved each way. The
// device backends report them per frame (StepReport::launches and the rows beside it).
#pragma once

namespace galsculpt {

struct DeviceCounters {
  long launches = 0;    // forEach (kernels)
  long reductions = 0;  // sum / maximum (two kernels each on the GPU)
  long reads = 0;       // host reads of device scalars
  long copies = 0;      // device-to-device copies
  long waits = 0;       // host synchronizations: reads, downloads, factorizations' status
  long graphs = 0;      // captured sections (one graph launch each on the GPU)
  double hostToDeviceBytes = 0.0, deviceToHostBytes = 0.0;
  // Kernels as a GPU runs them: launches, two per reduction, and copies.
  long kernels() const { return launches + 2 * reductions + copies; }
};

namespace detail {
// Bytes moved between host and device by this thread's buffers (uploads, mirrors, downloads):
// a buffer does not know its executor, and a frame's transfers are made on its own thread.
struct TransferBytes {
  double hostToDevice = 0.0, deviceToHost = 0.0;
};
inline thread_local TransferBytes transfers;
}  // namespace detail

}  // namespace galsculpt

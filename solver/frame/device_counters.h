// What a frame costs a device, counted by the executors (cpu_executor.h, and the CUDA one in
// gpu/cuda_executor.cuh): kernels, grid barriers, host waits and bytes moved each way. The
// device backends report them per frame (StepReport::launches and the rows beside it).
#pragma once

namespace galsculpt {

struct DeviceCounters {
  // What the frame asked for: each is a phase of a device program (a kernel of its own, two for
  // a reduction, where programs are off).
  long launches = 0;    // forEach
  long reductions = 0;  // sum / maximum: a pass over the items, one over the blocks
  long copies = 0;      // device-to-device copies
  // What the device ran: kernels (a device program each: the launches between two host
  // synchronizations as one kernel whose phases meet at grid-wide barriers), and those barriers.
  long programs = 0;
  long barriers = 0;
  long reads = 0;   // host reads of device scalars
  long waits = 0;   // host synchronizations: reads, downloads, factorizations' status
  long graphs = 0;  // graph launches (the CUDA executor with programs off)
  double hostToDeviceBytes = 0.0, deviceToHostBytes = 0.0;
  long kernels() const { return programs; }
};

namespace detail {
// Bytes moved between host and device by this thread's buffers (uploads, mirrors, downloads):
// a buffer does not know its executor, and a frame's transfers are made on its own thread.
struct TransferBytes {
  double hostToDevice = 0.0, deviceToHost = 0.0;
};
inline thread_local TransferBytes transfers;

// The device program open on this thread (an executor's launches since its last host
// synchronization, not yet run as one kernel), if any. A buffer's upload, allocation or release
// closes it first, so that device memory changes in the order the frame wrote it; a buffer does
// not know its executor.
struct OpenProgram {
  void (*close)(void* executor) = nullptr;
  void* executor = nullptr;
};
inline thread_local OpenProgram openProgram;
inline void closeOpenProgram() {
  const OpenProgram open = openProgram;
  openProgram = OpenProgram{};
  if (open.close) open.close(open.executor);
}
}  // namespace detail

}  // namespace galsculpt

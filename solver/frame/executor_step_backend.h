// The frame on an executor, behind the solver's StepBackend interface: "cpu" (cpu_backend.cpp),
// "cuda" on the GPU (gpu/cuda_step_backend.cu), "device-like" (device_like_backend.cpp). A device
// error mid-frame throws before the state is written back, so the caller may run the frame again
// elsewhere.
#pragma once

#include <string>

#include "solver/frame/frame_solver.h"
#include "solver/frame/step_backend.h"

namespace galsculpt {

template <typename Exec>
class ExecutorStepBackend final : public StepBackend {
 public:
  explicit ExecutorStepBackend(const SimModel& model) : solver_(executor_, model) {}
  std::string name() const override { return Exec::kName; }
  bool offloads() const override { return !Exec::kHostMemory; }
  StepReport step(SimState& state, const StepSettings& settings) override {
    const typename Exec::Counters before = executor_.counters();
    StepReport report = solver_.step(state, settings);
    executor_.flush();  // what the frame left open runs now, not at the next frame's first wait
    if constexpr (!Exec::kHostMemory) {  // what the frame cost a device (device_counters.h)
      const typename Exec::Counters after = executor_.counters();
      report.launches = static_cast<int>(after.kernels() - before.kernels());
      report.syncs = static_cast<int>(after.waits - before.waits);
      report.graphs = static_cast<int>(after.graphs - before.graphs);
      report.barriers = static_cast<int>(after.barriers - before.barriers);
      report.hostToDeviceBytes = after.hostToDeviceBytes - before.hostToDeviceBytes;
      report.deviceToHostBytes = after.deviceToHostBytes - before.deviceToHostBytes;
    }
    return report;
  }
  std::vector<double> carriedState() const override { return solver_.carriedState(); }
  void adoptCarriedState(std::vector<double> carried) override {
    solver_.adoptCarriedState(std::move(carried));
  }

 private:
  Exec executor_;
  FrameSolver<Exec> solver_;
};

}  // namespace galsculpt

// The frame on an executor, behind the solver's StepBackend interface: "cpu" (cpu_backend.cpp),
// "cuda" on the GPU (gpu/cuda_step_backend.cu), "device-like" in the tests. A device error
// mid-frame throws before the state is written back, so the caller may run the frame again
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
    return solver_.step(state, settings);
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

// The CPU backend: the frame (frame_solver.h) on the CPU executor, for the multigrid and the
// reference solver alike. The template is instantiated once, in cpu_backend.cpp.
#pragma once

#include <memory>
#include <vector>

#include "solver/frame/step_backend.h"

namespace galsculpt {

class CpuStepBackend final : public StepBackend {
 public:
  explicit CpuStepBackend(const SimModel& model);
  ~CpuStepBackend() override;
  std::string name() const override { return "cpu"; }
  bool offloads() const override { return false; }
  StepReport step(SimState& state, const StepSettings& settings) override;
  std::vector<double> carriedState() const override { return frame_->carriedState(); }
  void adoptCarriedState(std::vector<double> carried) override {
    frame_->adoptCarriedState(std::move(carried));
  }

 private:
  std::unique_ptr<StepBackend> frame_;
};

// Each edge's stress as the fracture pass sees it at the state's positions (element maximum,
// then the model's fracture field's kernel mean), 0 on damaged edges: the pass's own kernels,
// for tests and views. Throws std::invalid_argument when the model's field is not enabled.
std::vector<double> fractureEdgeStress(const SimModel& model, const SimState& state);

}  // namespace galsculpt

#include "solver/frame/cpu_backend.h"

#include <stdexcept>

#include "solver/frame/cpu_executor.h"
#include "solver/frame/executor_step_backend.h"

namespace galsculpt {

CpuStepBackend::CpuStepBackend(const SimModel& model)
    : frame_(std::make_unique<ExecutorStepBackend<CpuExecutor>>(model)) {}

CpuStepBackend::~CpuStepBackend() = default;

StepReport CpuStepBackend::step(SimState& state, const StepSettings& settings) {
  return frame_->step(state, settings);
}

std::vector<double> fractureEdgeStress(const SimModel& model, const SimState& state) {
  if (!model.fracture.enabled)
    throw std::invalid_argument("fractureEdgeStress: the model has no fracture field");
  const StepSettings settings;
  CpuExecutor ex;
  FrameSolver<CpuExecutor> frame(ex, model);
  return frame.edgeStress(state, settings);
}

}  // namespace galsculpt

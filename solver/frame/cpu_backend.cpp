#include "solver/frame/cpu_backend.h"

#include "solver/frame/cpu_executor.h"
#include "solver/frame/frame_solver.h"

namespace galsculpt {

CpuStepBackend::CpuStepBackend(const SimModel& model)
    : frame_(std::make_unique<ExecutorStepBackend<CpuExecutor>>(model)) {}

CpuStepBackend::~CpuStepBackend() = default;

StepReport CpuStepBackend::step(SimState& state, const StepSettings& settings) {
  return frame_->step(state, settings);
}

std::vector<double> fractureEdgeStress(const SimModel& model, const FractureField& field,
                                       const SimState& state) {
  StepSettings settings;
  settings.fracture = std::shared_ptr<const FractureField>(&field, [](const FractureField*) {});
  CpuExecutor ex;
  FrameSolver<CpuExecutor> frame(ex, model);
  return frame.edgeStress(state, settings);
}

}  // namespace galsculpt

// Which backend computes a scene's frames: the scene's `solver.backend` (or the command line's
// --backend), auto | cpu | cuda, against what this build and this machine have. auto takes the
// GPU when one works; whenever the choice falls back to the CPU, the note says why.
#pragma once

#include <memory>
#include <string>

#include "engine/scene/scene.h"
#include "solver/frame/cpu_backend.h"

namespace galsculpt {

struct BackendChoice {
  std::unique_ptr<StepBackend> backend;
  std::string note;      // why an explicit request (cuda) was not met: said to the user
  std::string fallback;  // why `auto` runs on the CPU: asked for, not said (Simulation)
};

// The model must outlive the backend.
BackendChoice chooseBackend(BackendRequest requested, const SimModel& model,
                            const StepSettings& settings);

}  // namespace galsculpt

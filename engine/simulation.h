// A scene turned into a running simulation: the solver model, its state and step settings,
// plus per-frame metrics. The engine's one place where scene descriptions meet the solver.
#pragma once

#include <string>
#include <vector>

#include "engine/scene.h"
#include "solver/step.h"

namespace galsculpt {

enum class SolverChoice { FromScene, Reference };

struct FrameMetrics {
  int frame = 0;
  double timeS = 0.0;
  double msTotal = 0.0, msElements = 0.0, msSolve = 0.0, msPlastic = 0.0, msOther = 0.0;
  double volume = 0.0, volumeChangePct = 0.0;
  double kineticEnergy = 0.0, elasticEnergy = 0.0;
  double residual = 0.0;
  double maxDisplacement = 0.0;
  int damagedEdges = 0, pieces = 0, warnings = 0, newtonIterations = 0;
  double contactForceN = 0.0;  // magnitude of the summed collider forces
};

// CSV header and row, in the column order documented in docs/cli.md.
std::string metricsCsvHeader();
std::string metricsCsvRow(const FrameMetrics& m);

// Solver-side material from a scene material; throws InputError for an unknown model.
MaterialParams materialFromScene(const MaterialDesc& m);

class Simulation {
 public:
  // Throws InputError (naming the scene and JSON path) for anchors that select nothing or
  // name vertices that do not exist.
  Simulation(const SceneDescription& scene, const TetMesh& mesh,
             SolverChoice choice = SolverChoice::FromScene);

  FrameMetrics advance();

  const SimModel& model() const { return model_; }
  const SimState& state() const { return state_; }
  const StepSettings& settings() const { return settings_; }
  // Notes for the user about how the scene is run (e.g. a solver that is not available yet).
  const std::vector<std::string>& notes() const { return notes_; }
  int frame() const { return frame_; }
  // The tet mesh's boundary at the current positions.
  TriMesh surface() const;
  double currentVolume() const;

 private:
  SimModel model_;
  SimState state_;
  StepSettings settings_;
  std::vector<std::string> notes_;
  std::vector<Tri> boundary_;
  double restVolume_ = 0.0;
  int frame_ = 0;
};

}  // namespace galsculpt

// Runs a scene on the CPU backend and on another backend from the same state and compares them
// frame by frame (the CUDA backend's tests).
#pragma once

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "engine/scene/scene.h"
#include "engine/scene/scene_mesh.h"
#include "engine/session/simulation.h"
#include "solver/fracture/knife.h"
#include "solver/frame/cpu_backend.h"

namespace galsculpt {

// The named scene of assets/scenes with a smaller mesh.
inline SceneDescription sceneNamed(const std::string& name, int tets) {
  SceneDescription s = loadScene(std::filesystem::path(GALSCULPT_SOURCE_DIR) / "assets" / "scenes" /
                                 (name + ".json"));
  s.mesh.tets = tets;
  return s;
}

// The scene with the paper's one linearized step a frame (the Charpy scene's solver before it
// moved to converged frames): the executor comparisons need the same equations on both sides,
// not converged ones, and cost a fraction.
inline SceneDescription withPaperSolver(SceneDescription s) {
  const std::string grid = s.solver.grid;
  s.solver = solverPreset(SolverPreset::Paper);
  s.solver.grid = grid;
  return s;
}

struct Comparison {
  double maxRelativeError = 0.0;  // largest |x_dev - x_cpu| over the largest displacement
  int cpuDamaged = 0, deviceDamaged = 0;
};

// Runs `frames` frames on both backends from the same state; positions are compared after
// every frame, relative to the largest displacement from the start.
inline Comparison compareWithCpu(const Simulation& sim, StepBackend& backend, int frames,
                                 StepSettings settings = {}) {
  if (settings.gridHandles.empty() || !settings.multigrid) settings = sim.settings();
  SimState cpu = sim.state();
  SimState device = sim.state();
  CpuStepBackend cpuBackend(sim.model());
  Comparison c;
  const std::vector<Vec3> start = cpu.x;
  for (int f = 0; f < frames; ++f) {
    const StepReport rc = cpuBackend.step(cpu, settings);
    const StepReport rd = backend.step(device, settings);
    EXPECT_EQ(rc.retries, rd.retries) << "frame " << f;
    if (std::getenv("GALSCULPT_DEBUG_COMPARE"))
      std::printf("frame %d: damaged %d / %d, ratio %.9g / %.9g, backtracks %d / %d\n", f,
                  rc.newlyDamaged, rd.newlyDamaged, rc.maxStressRatio, rd.maxStressRatio,
                  rc.backtracks, rd.backtracks);
    double displacement = 1e-12, error = 0.0;
    for (size_t v = 0; v < cpu.x.size(); ++v) {
      displacement = std::max(displacement, (cpu.x[v] - start[v]).norm());
      error = std::max(error, (cpu.x[v] - device.x[v]).norm());
      EXPECT_TRUE(device.x[v].allFinite());
    }
    c.maxRelativeError = std::max(c.maxRelativeError, error / displacement);
    EXPECT_NEAR(cpu.time, device.time, 1e-12);
  }
  double moved = 0.0;
  for (size_t v = 0; v < cpu.x.size(); ++v) moved = std::max(moved, (cpu.x[v] - start[v]).norm());
  std::printf("%d frames, %d tets: largest displacement %.3g m, largest relative difference %.3g\n",
              frames, sim.model().numTets(), moved, c.maxRelativeError);
  EXPECT_GT(moved, 0.0) << "the scene must move for the comparison to mean anything";
  for (auto d : cpu.damaged) c.cpuDamaged += d;
  for (auto d : device.damaged) c.deviceDamaged += d;
  return c;
}

}  // namespace galsculpt

// Runs a scene on the CPU backend and on another backend from the same state and compares them
// frame by frame (the CUDA backend's tests).
#pragma once

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
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
  if (settings.gridHandles.empty() || !settings.multigrid()) settings = sim.settings();
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

// The positions after each of `frames` frames of `backend` from the simulation's state, with
// every frame's report.
struct Trajectory {
  std::vector<std::vector<Vec3>> x;
  std::vector<StepReport> reports;
};
inline Trajectory trajectory(const Simulation& sim, StepBackend& backend, int frames,
                             const StepSettings& settings) {
  SimState state = sim.state();
  Trajectory t;
  for (int f = 0; f < frames; ++f) {
    t.reports.push_back(backend.step(state, settings));
    t.x.push_back(state.x);
  }
  return t;
}

// The largest distance between `a` and `b` at each frame over the largest displacement of `b`
// from `start` up to that frame; the maximum over all frames.
inline double relativeDifference(const Trajectory& a, const Trajectory& b,
                                 const std::vector<Vec3>& start, const char* label = nullptr) {
  double moved = 1e-12, worst = 0.0;
  for (size_t f = 0; f < a.x.size(); ++f) {
    double error = 0.0;
    for (size_t v = 0; v < start.size(); ++v) {
      moved = std::max(moved, (b.x[f][v] - start[v]).norm());
      error = std::max(error, (a.x[f][v] - b.x[f][v]).norm());
    }
    worst = std::max(worst, error / moved);
    if (label && std::getenv("GALSCULPT_DEBUG_COMPARE"))
      std::printf(
          "%s frame %zu: moved %.4g m, difference %.4g m (%.3g), newton %d / %d, cg %d / %d,"
          " residual %.3g / %.3g\n",
          label, f, moved, error, error / moved, a.reports[f].newtonIterations,
          b.reports[f].newtonIterations, a.reports[f].cgIterations, b.reports[f].cgIterations,
          a.reports[f].residual, b.reports[f].residual);
  }
  return worst;
}

// The settings solved far past the scene's tolerance: what both backends then compute is the
// frame's solution up to round-off, whatever path each takes to it.
inline StepSettings tightlyConverged(StepSettings s) {
  s.residualTolerance = 1e-9;
  s.newtonIterations = 40;
  s.pcgTolerance = 1e-12;
  s.pcgMaxIterations = 1000;
  return s;
}

// The hanging sphere (6k tets), uncut.
inline std::unique_ptr<Simulation> hangingSphere() {
  const SceneDescription scene = sceneNamed("hanging_sphere", 6000);
  return std::make_unique<Simulation>(scene, loadSceneMesh(scene));
}

// The hanging sphere (6k tets) cut twice: two pieces fall free of the anchored cap (the pieces'
// own starts, coarse solves and residuals).
inline std::unique_ptr<Simulation> cutSphere() {
  const SceneDescription scene = sceneNamed("hanging_sphere", 6000);
  auto sim = std::make_unique<Simulation>(scene, loadSceneMesh(scene));
  sim->cut(sweptBladeSurface(Vec3(-1, 0.01, -1), Vec3(-1, 0.01, 1), Vec3(1, 0.01, -1),
                             Vec3(1, 0.01, 1)));
  sim->cut(sweptBladeSurface(Vec3(-1, -0.085, -1), Vec3(-1, -0.085, 1), Vec3(1, -0.085, -1),
                             Vec3(1, -0.085, 1)));
  return sim;
}

// The hanging sphere (6k tets) cut in two halves from top to bottom: both stay anchored, their
// crack faces at rest where the knife left them (ties between a closed and an open crack).
inline std::unique_ptr<Simulation> splitSphere() {
  const SceneDescription scene = sceneNamed("hanging_sphere", 6000);
  auto sim = std::make_unique<Simulation>(scene, loadSceneMesh(scene));
  sim->cut(sweptBladeSurface(Vec3(0.01, -1, -1), Vec3(0.01, -1, 1), Vec3(0.01, 1, -1),
                             Vec3(0.01, 1, 1)));
  return sim;
}

// Two questions per scene. Solved far past the scene's tolerance, both backends compute the
// frames' solution, and `other` differs from the CPU by round-off grown over the frames (on a GPU
// the same double-precision arithmetic in another order: fused multiply-adds, tree reductions).
// At the scene's own tolerance (a residual of 1 % of the force scale) each stops somewhere within
// it, by its own path (the CPU reuses coarse factors, the device paths refactor them densely), so
// the two may differ by what the tolerance allows: there `other` must be as near the tight
// solution as the CPU is.
// (GALSCULPT_COMPARE_FRAMES=N runs N frames instead: a shorter run under a memory checker.)
inline void expectSolvesAsTheCpuDoes(const Simulation& sim, StepBackend& other, int frames) {
  if (const char* n = std::getenv("GALSCULPT_COMPARE_FRAMES")) frames = std::max(1, std::atoi(n));
  const StepSettings own = sim.settings();
  const StepSettings tight = tightlyConverged(own);
  CpuStepBackend cpu(sim.model());
  const std::vector<Vec3> start = sim.state().x;
  const Trajectory cpuTight = trajectory(sim, cpu, frames, tight);
  const Trajectory cpuOwn = trajectory(sim, cpu, frames, own);
  const double cpuSlack = relativeDifference(cpuOwn, cpuTight, start, "cpu own / tight");
  for (const StepReport& r : cpuTight.reports) EXPECT_LT(r.residual, 1e-5);
  const Trajectory otherTight = trajectory(sim, other, frames, tight);
  const Trajectory otherOwn = trajectory(sim, other, frames, own);
  const double tightDiff = relativeDifference(otherTight, cpuTight, start, "other / cpu tight");
  const double otherSlack = relativeDifference(otherOwn, cpuTight, start, "other own / cpu tight");
  std::printf(
      "%s against cpu, tight: %.3g; at the scene's tolerance, from the tight solution: "
      "%s %.3g, cpu %.3g\n",
      other.name().c_str(), tightDiff, other.name().c_str(), otherSlack, cpuSlack);
  EXPECT_LT(tightDiff, 1e-6);
  EXPECT_LE(otherSlack, 2.0 * cpuSlack + 1e-6);
  for (size_t f = 0; f < otherOwn.reports.size(); ++f)
    EXPECT_EQ(otherOwn.reports[f].converged, cpuOwn.reports[f].converged) << "frame " << f;
}

}  // namespace galsculpt

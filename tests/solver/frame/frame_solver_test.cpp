// The frame (solver/frame/frame_solver.h) on the CPU executor: bit-identical results for any
// thread count on every path (fracture, cut pieces and fragments, plasticity, colliders, every
// solver option), the retry discipline, the launch budget the CUDA executor inherits, and the
// capture rules. The CUDA executor is checked against it in tests/gpu (on a GPU).
#include "solver/frame/frame_solver.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "solver/fracture/knife.h"
#include "solver/frame/cpu_executor.h"
#include "tests/gpu/backend_comparison.h"

namespace galsculpt {
namespace {

// `frames` frames at 1 and at 2 threads from the same state; every position, velocity and
// damage flag must be the same bits.
void expectSameAtOneAndTwoThreads(const Simulation& sim, int frames, StepSettings settings = {}) {
  if (!settings.multigrid() && settings.gridHandles == StepSettings{}.gridHandles)
    settings = sim.settings();
  std::vector<SimState> results;
  const int threads = threadCount();
  for (int t : {1, 2}) {
    setThreadCount(t);
    CpuStepBackend cpu(sim.model());
    SimState state = sim.state();
    for (int f = 0; f < frames; ++f) cpu.step(state, settings);
    results.push_back(state);
  }
  setThreadCount(threads);
  const SimState &a = results[0], &b = results[1];
  double moved = 0.0;
  for (size_t v = 0; v < a.x.size(); ++v)
    moved = std::max(moved, (a.x[v] - sim.state().x[v]).norm());
  EXPECT_GT(moved, 0.0) << "the scene must move for the comparison to mean anything";
  EXPECT_EQ(a.x, b.x);
  EXPECT_EQ(a.v, b.v);
  EXPECT_EQ(a.damaged, b.damaged);
  EXPECT_EQ(a.plasticStrain, b.plasticStrain);
}

TEST(FrameSolver, HangingSphereIsTheSameAtOneAndTwoThreads) {
  const SceneDescription scene = sceneNamed("hanging_sphere", 6000);
  const Simulation sim(scene, loadSceneMesh(scene));
  expectSameAtOneAndTwoThreads(sim, 20);
}

// A cut across the sphere (two pieces: the coarsest per-piece start) and one through its
// bottom cap (a loose fragment: the fragment correction), falling apart.
TEST(FrameSolver, CutSphereIsTheSameAtOneAndTwoThreads) {
  const SceneDescription scene = sceneNamed("hanging_sphere", 6000);
  Simulation sim(scene, loadSceneMesh(scene));
  ASSERT_GT(sim.cut(sweptBladeSurface(Vec3(-1, 0.01, -1), Vec3(-1, 0.01, 1), Vec3(1, 0.01, -1),
                                      Vec3(1, 0.01, 1))),
            0);
  ASSERT_GT(sim.cut(sweptBladeSurface(Vec3(-1, -0.085, -1), Vec3(-1, -0.085, 1),
                                      Vec3(1, -0.085, -1), Vec3(1, -0.085, 1))),
            0);
  Multigrid probe(sim.model().pattern, sim.model().mesh.vertices, sim.model().edges,
                  sim.settings().gridHandles);
  probe.updateDamage(sim.model().edges, sim.state().damaged, 1);
  EXPECT_GE(probe.pieceCount(), 2) << "the per-piece coarse start is exercised";
  EXPECT_GE(probe.fragmentStart().size(), 2u) << "a fragment correction is exercised";
  expectSameAtOneAndTwoThreads(sim, 20);
}

// Colliders (a moving pendulum striker), non-local fracture with a compressive threshold.
TEST(FrameSolver, CharpyBarIsTheSameAtOneAndTwoThreads) {
  SceneDescription scene = withPaperSolver(sceneNamed("charpy", 8000));
  scene.fracture.threshold = 1.0e9;  // cracks within the frames
  // What these frames cover: non-local fracture (the scene's own is local) at fixed thresholds.
  scene.fracture.kernelRadius = 0.0005;
  scene.fracture.energy = 0.0;
  const Simulation sim(scene, loadSceneMesh(scene));
  CpuStepBackend probe(sim.model());
  SimState state = sim.state();
  for (int f = 0; f < 60; ++f) probe.step(state, sim.settings());
  int damaged = 0;
  for (auto d : state.damaged) damaged += d;
  EXPECT_GT(damaged, 100) << "the comparison must cover fracture";
  expectSameAtOneAndTwoThreads(sim, 60);
}

// Plastic flow (clay sagging under gravity).
TEST(FrameSolver, PlasticSphereIsTheSameAtOneAndTwoThreads) {
  SceneDescription scene = sceneNamed("hanging_sphere", 6000);
  scene.material.preset = "clay";
  scene.material.yieldStress = 100.0;
  const Simulation sim(scene, loadSceneMesh(scene));
  ASSERT_FALSE(sim.state().plasticInverse.empty());
  expectSameAtOneAndTwoThreads(sim, 20);
}

// Every solver option: Jacobi smoothing, a dense coarse Cholesky, PCG, three levels, Newton
// iterations with line search and frozen damping, sub-steps, and the reference's direct solve.
TEST(FrameSolver, SolverOptionsAreTheSameAtOneAndTwoThreads) {
  const SceneDescription scene = sceneNamed("hanging_sphere", 6000);
  const Simulation sim(scene, loadSceneMesh(scene));
  struct Variant {
    const char* name;
    void (*apply)(StepSettings&);
  };
  const Variant variants[] = {
      {"jacobi", [](StepSettings& s) { s.smoother = Smoother::Jacobi; }},
      {"cholesky", [](StepSettings& s) { s.coarseSolver = CoarseSolver::Cholesky; }},
      {"pcg", [](StepSettings& s) { s.pcgTolerance = 1e-6; }},
      {"three levels",
       [](StepSettings& s) {
         s.gridHandles = {200, 30};
       }},
      {"newton",
       [](StepSettings& s) {
         s.newtonIterations = 3;
         s.lineSearch = true;
       }},
      {"substeps", [](StepSettings& s) { s.substeps = 2; }},
      {"reference", [](StepSettings& s) { s = referenceSettings(s); }},
  };
  for (const Variant& v : variants) {
    SCOPED_TRACE(v.name);
    StepSettings settings = sim.settings();
    v.apply(settings);
    expectSameAtOneAndTwoThreads(sim, 8, settings);
  }
}

}  // namespace
}  // namespace galsculpt

namespace galsculpt {
namespace {

// A NaN velocity: every sub-step fails, is rolled back and retried with half the step, and the
// frame gives up with the positions of the last good state, as on the CPU.
TEST(FrameSolver, FailedSubstepsAreRolledBackAndCountedAsOnTheCpu) {
  const SceneDescription scene = sceneNamed("hanging_sphere", 6000);
  const Simulation sim(scene, loadSceneMesh(scene));
  SimState device = sim.state();
  device.v[3] = Vec3(std::nan(""), 0, 0);
  const std::vector<Vec3> before = device.x;
  StepSettings settings = sim.settings();
  settings.maxRetries = 3;
  CpuExecutor ex;
  FrameSolver<CpuExecutor> solver(ex, sim.model());
  const StepReport r = solver.step(device, settings);
  EXPECT_EQ(r.retries, settings.maxRetries + 1);
  EXPECT_NEAR(device.time, settings.dt, 1e-15);
  EXPECT_EQ(device.x, before);
  // The next frame starts from the host's state again (a tool fixed the velocity).
  device.v[3] = Vec3::Zero();
  EXPECT_EQ(solver.step(device, settings).retries, 0);
  EXPECT_NE(device.x, before);
}

// The launch budget of a frame (what the CUDA executor issues, mostly inside graphs), measured
// on the host executor for the hanging sphere's setting: printed for docs/benchmarks.md, and
// bounded so that a change that multiplies launches or host synchronizations shows.
TEST(FrameSolver, LaunchesAndHostReadsPerFrame) {
  SceneDescription scene = sceneNamed("hanging_sphere", 6000);
  scene.solver = solverPreset(SolverPreset::Paper);  // the captured, read-free Newton step
  const Simulation sim(scene, loadSceneMesh(scene));
  SimState state = sim.state();
  CpuExecutor ex;
  FrameSolver<CpuExecutor> solver(ex, sim.model());
  solver.step(state, sim.settings());  // uploads and the first hierarchy
  const CpuExecutor::Counters before = ex.counters();
  const int frames = 10;
  for (int f = 0; f < frames; ++f) solver.step(state, sim.settings());
  const CpuExecutor::Counters& after = ex.counters();
  const double launches = double(after.launches - before.launches) / frames;
  const double reductions = double(after.reductions - before.reductions) / frames;
  const double reads = double(after.reads - before.reads) / frames;
  std::printf(
      "per frame (50/all, 3+3 GS sweeps, 20 coarse CG): %.0f launches, %.0f reductions, "
      "%.1f host reads\n",
      launches, reductions, reads);
  EXPECT_LE(reads, 3.0) << "one per Newton iteration and one per sub-step end (+ backtracks)";
  EXPECT_LT(launches + 2 * reductions, 600.0);
}

// What the CUDA executor records as a graph may not read, allocate or wait; the host executor
// refuses those inside captured(), so the frame tests above check the CUDA path's discipline.
TEST(CpuExecutor, CapturedSectionsMayNotReadAllocateOrWait) {
  CpuExecutor ex;
  CpuExecutor::Buffer<double> b;
  b.resize(4);
  double value = 0.0;
  EXPECT_THROW(ex.captured(0, 1, [&] { ex.read(b.data(), &value, 1); }), std::logic_error);
  EXPECT_THROW(ex.captured(0, 1, [&] { b.resize(8); }), std::logic_error);
  EXPECT_THROW(ex.captured(0, 1, [&] { b.upload(std::vector<double>{1.0}); }), std::logic_error);
  EXPECT_THROW(ex.captured(0, 1, [&] { ex.denseCholesky(2, b.data(), b.data() + 3); }),
               std::logic_error);
  // Launches and device-side reductions are what a section is made of.
  double* p = b.data();
  EXPECT_NO_THROW(ex.captured(0, 1, [&] {
    ex.forEach(4, [=](int i) { p[i] = i + 1.0; });
    ex.sum(
        4, [=](int i) { return p[i]; }, p + 3);
  }));
  ex.read(p + 3, &value, 1);
  EXPECT_EQ(value, 1.0 + 2.0 + 3.0 + 4.0);
}

}  // namespace
}  // namespace galsculpt

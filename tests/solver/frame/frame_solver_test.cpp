// The device backend's frame (solver/frame/frame_solver.h) run by the host executor against the CPU
// backend, frame by frame: the kernels, gathers, multigrid, line search, contact, plasticity
// and fracture the GPU runs, checked on machines without one. Scenes are the paper's, smaller.
#include "solver/frame/frame_solver.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "solver/frame/cpu_executor.h"
#include "tests/gpu/backend_comparison.h"

namespace galsculpt::gpu {
namespace {

Comparison compare(const Simulation& sim, int frames, StepSettings settings = {}) {
  DeviceStepBackend<HostExecutor> backend(sim.model());
  return compareWithCpu(sim, backend, frames, settings);
}

TEST(DeviceSolver, HangingSphereMatchesTheCpuFor100Frames) {
  const SceneDescription scene = sceneNamed("hanging_sphere", 6000);
  const Simulation sim(scene, loadSceneMesh(scene));
  const Comparison c = compare(sim, 100);
  EXPECT_LT(c.maxRelativeError, 1e-6) << "double precision on both sides";
}

// A cut across the sphere (two pieces: the coarsest per-piece start) and one through its
// bottom cap (a loose fragment: the fragment correction), then 100 frames falling apart.
TEST(DeviceSolver, CutSphereMatchesTheCpuFor100Frames) {
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
  const Comparison c = compare(sim, 100);
  EXPECT_LT(c.maxRelativeError, 1e-6);
}

// Colliders (a moving pendulum striker), non-local fracture with a compressive threshold. A
// crack amplifies round-off (which edge breaks first decides the rest): at this threshold both
// backends break the same edges in every frame and the positions agree to 6e-8 of the motion
// after 100 frames; at 0.2 GPa the bar shatters and single edges differ from frame 46 on.
TEST(DeviceSolver, CharpyBarMatchesTheCpuFor100Frames) {
  SceneDescription scene = sceneNamed("charpy", 8000);
  scene.fracture.threshold = 1.0e9;  // cracks within the 100 frames
  const Simulation sim(scene, loadSceneMesh(scene));
  const Comparison c = compare(sim, 100);
  EXPECT_LT(c.maxRelativeError, 1e-5);
  EXPECT_GT(c.cpuDamaged, 100) << "the comparison must cover fracture";
  EXPECT_EQ(c.deviceDamaged, c.cpuDamaged);
}

// Plastic flow (clay sagging under gravity).
TEST(DeviceSolver, PlasticSphereMatchesTheCpu) {
  SceneDescription scene = sceneNamed("hanging_sphere", 6000);
  scene.material.preset = "clay";
  scene.material.yieldStress = 100.0;
  const Simulation sim(scene, loadSceneMesh(scene));
  ASSERT_FALSE(sim.state().plasticInverse.empty());
  const Comparison c = compare(sim, 30);
  EXPECT_LT(c.maxRelativeError, 1e-6);
}

// Every solver option the device mirrors: Jacobi smoothing, a dense coarse Cholesky, PCG,
// three levels, Newton iterations with line search and frozen damping, sub-steps.
TEST(DeviceSolver, SolverOptionsMatchTheCpu) {
  const SceneDescription scene = sceneNamed("hanging_sphere", 6000);
  const Simulation sim(scene, loadSceneMesh(scene));
  struct Variant {
    const char* name;
    void (*apply)(StepSettings&);
  };
  const Variant variants[] = {
      {"jacobi", [](StepSettings& s) { s.multigridSettings.jacobi = true; }},
      {"cholesky", [](StepSettings& s) { s.multigridSettings.coarseCholesky = true; }},
      {"pcg", [](StepSettings& s) { s.multigridSettings.pcg = true; }},
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
  };
  for (const Variant& v : variants) {
    StepSettings settings = sim.settings();
    v.apply(settings);
    const Comparison c = compare(sim, 15, settings);
    EXPECT_LT(c.maxRelativeError, 1e-6) << v.name;
  }
}

}  // namespace
}  // namespace galsculpt::gpu

namespace galsculpt::gpu {
namespace {

// A NaN velocity: every sub-step fails, is rolled back and retried with half the step, and the
// frame gives up with the positions of the last good state, as on the CPU.
TEST(DeviceSolver, FailedSubstepsAreRolledBackAndCountedAsOnTheCpu) {
  const SceneDescription scene = sceneNamed("hanging_sphere", 6000);
  const Simulation sim(scene, loadSceneMesh(scene));
  SimState device = sim.state();
  device.workspace = nullptr;
  device.v[3] = Vec3(std::nan(""), 0, 0);
  const std::vector<Vec3> before = device.x;
  StepSettings settings = sim.settings();
  settings.maxRetries = 3;
  HostExecutor ex;
  DeviceSolver<HostExecutor> solver(ex, sim.model());
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
TEST(DeviceSolver, LaunchesAndHostReadsPerFrame) {
  const SceneDescription scene = sceneNamed("hanging_sphere", 6000);
  const Simulation sim(scene, loadSceneMesh(scene));
  SimState state = sim.state();
  state.workspace = nullptr;
  HostExecutor ex;
  DeviceSolver<HostExecutor> solver(ex, sim.model());
  solver.step(state, sim.settings());  // uploads and the first hierarchy
  const HostExecutor::Counters before = ex.counters();
  const int frames = 10;
  for (int f = 0; f < frames; ++f) solver.step(state, sim.settings());
  const HostExecutor::Counters& after = ex.counters();
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
TEST(HostExecutor, CapturedSectionsMayNotReadAllocateOrWait) {
  HostExecutor ex;
  HostExecutor::Buffer<double> b;
  b.resize(4);
  double value = 0.0;
  EXPECT_THROW(ex.captured(0, 1, [&] { ex.read(b.data(), &value, 1); }), std::logic_error);
  EXPECT_THROW(ex.captured(0, 1, [&] { b.resize(8); }), std::logic_error);
  EXPECT_THROW(ex.captured(0, 1, [&] { b.upload(std::vector<double>{1.0}); }), std::logic_error);
  EXPECT_THROW(ex.captured(0, 1, [&] { ex.denseCholesky(2, b.data()); }), std::logic_error);
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
}  // namespace galsculpt::gpu

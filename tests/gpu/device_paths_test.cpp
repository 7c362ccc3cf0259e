// The frame's device paths, run on the CPU (DeviceLikeExecutor): the same scenes as the CUDA
// backend's tests, everywhere, so that a defect of those paths shows without a GPU.
#include <gtest/gtest.h>

#include <cstdio>

#include "solver/frame/device_like_backend.h"
#include "solver/frame/device_like_executor.h"
#include "solver/frame/executor_step_backend.h"
#include "tests/gpu/backend_comparison.h"

namespace galsculpt {

namespace {

void expectDevicePathsSolveAsTheCpuDoes(const Simulation& sim, int frames) {
  ExecutorStepBackend<DeviceLikeExecutor> device(sim.model());
  expectSolvesAsTheCpuDoes(sim, device, frames);
}

TEST(DevicePaths, HangingSphereSolvesAsOnTheCpu) {
  expectDevicePathsSolveAsTheCpuDoes(*hangingSphere(), 30);
}

TEST(DevicePaths, CutSphereSolvesAsOnTheCpu) {
  expectDevicePathsSolveAsTheCpuDoes(*cutSphere(), 30);
}

TEST(DevicePaths, SplitSphereSolvesAsOnTheCpu) {
  expectDevicePathsSolveAsTheCpuDoes(*splitSphere(), 30);
}

// The paper's one linearized step (one V-cycle, no CG): the smoother is the solve there, and a
// device smooths as the CPU does (Gauss-Seidel, `smoother: auto`), so the two agree to
// round-off; with Jacobi on the device they were 0.86 of the motion apart on Charpy.
TEST(DevicePaths, ThePapersStepSolvesAsOnTheCpu) {
  const SceneDescription scene = withPaperSolver(sceneNamed("hanging_sphere", 6000));
  const Simulation sim(scene, loadSceneMesh(scene));
  ExecutorStepBackend<DeviceLikeExecutor> device(sim.model());
  EXPECT_LT(compareWithCpu(sim, device, 10).maxRelativeError, 1e-9);
}

// What the GPU comparisons assume: solved tightly, a frame's solution moves by round-off when
// its start does. The split sphere's crack faces sit at rest where the knife left them, a tie
// between open and closed cracks on thousands of edges; the start moved by a few last bits once
// closed another set of them, and with it the damping's stiffness frozen at the start: the
// first frame's solutions were a quarter of its motion apart.
TEST(DevicePaths, TightSolutionsMoveByRoundOffWithTheStart) {
  const auto sim = splitSphere();
  const StepSettings tight = tightlyConverged(sim->settings());
  CpuStepBackend cpu(sim->model());
  const int frames = 3;
  const Trajectory exact = trajectory(*sim, cpu, frames, tight);
  SimState moved = sim->state();
  for (size_t v = 0; v < moved.x.size(); ++v)
    moved.x[v] += Vec3(1e-16 * static_cast<double>(static_cast<int>((v * 7919) % 17) - 8), 0, 0);
  Trajectory perturbed;
  for (int f = 0; f < frames; ++f) {
    perturbed.reports.push_back(cpu.step(moved, tight));
    perturbed.x.push_back(moved.x);
  }
  EXPECT_LT(relativeDifference(perturbed, exact, sim->state().x, "perturbed / exact"), 1e-9);
}

// What a frame costs a device, counted on the CPU by the device-like backend
// (device_counters.h): kernels (device programs: the launches between two host waits as one
// kernel), the grid barriers inside them (a phase each), host waits and bytes a frame, as means
// over frames 2-11 (the first uploads the model). Printed, and bounded about a twentieth above
// the counts (the counts are deterministic), so that a change that adds a wait, a kernel or a
// pass of launches per Newton iteration fails; lower the bounds as the device path improves
// (the target: 60 kernels and 4 waits on the sphere). The history is in docs/notes (2026-12-07
// to 2026-12-08): PCG's decisions on the device, the residual test on the trials' read, PCG as
// a loop the device tests with its figures in the frame's read (the region's solve's too), the
// local region's threshold found on the device, the sub-step's end from the accepted trial's
// read, device programs, the coarse factorization's status on the Newton read, the null-step
// test only where the last step was null, the sub-step's end in one wait, the pieces' start
// without reads, the local region and the pieces' residuals formed at each trial, the fracture
// pass's search read with the sub-step's end.
struct DeviceFrameCost {
  double kernels = 0.0, barriers = 0.0, syncs = 0.0, hostToDevice = 0.0, deviceToHost = 0.0;
};
DeviceFrameCost deviceFrameCost(const Simulation& sim, const char* name, int settle = 1) {
  const std::unique_ptr<StepBackend> device = makeDeviceLikeStepBackend(sim.model());
  SimState state = sim.state();
  for (int f = 0; f < settle; ++f) device->step(state, sim.settings());
  DeviceFrameCost c;
  const int frames = 10;
  for (int f = 0; f < frames; ++f) {
    const StepReport r = device->step(state, sim.settings());
    EXPECT_TRUE(r.converged) << name << " frame " << f + 2;
    c.kernels += r.launches / double(frames);
    c.syncs += r.syncs / double(frames);
    c.barriers += r.barriers / double(frames);
    c.hostToDevice += r.hostToDeviceBytes / frames;
    c.deviceToHost += r.deviceToHostBytes / frames;
  }
  std::printf(
      "%s, a frame on a device: %.1f kernels, %.0f grid barriers, %.1f host waits, %.0f bytes "
      "up, %.0f bytes down\n",
      name, c.kernels, c.barriers, c.syncs, c.hostToDevice, c.deviceToHost);
  return c;
}

TEST(DeviceCounts, TheHangingSpheresFrameStaysWithinItsLaunchesAndWaits) {
  const DeviceFrameCost c = deviceFrameCost(*hangingSphere(), "hanging sphere (6k, converged)");
  EXPECT_GT(c.kernels, 0.0);
  EXPECT_LE(c.kernels, 8.4);
  EXPECT_LE(c.barriers, 393.0);
  EXPECT_LE(c.syncs, 3.1) << "the issue's target on the sphere: 4";
  EXPECT_LE(c.hostToDevice, 1024.0) << "a frame uploads only what changed (anchor targets)";
}

TEST(DeviceCounts, TheCutSpheresFrameStaysWithinItsLaunchesAndWaits) {
  const DeviceFrameCost c = deviceFrameCost(*cutSphere(), "cut sphere (6k, two pieces falling)");
  EXPECT_LE(c.kernels, 11.0);
  EXPECT_LE(c.barriers, 725.0);
  EXPECT_LE(c.syncs, 4.8);
}

// Charpy's bar (8k tets, its converged scene) after the break: frames 41-50, the halves in
// flight with their crack faces touching.
TEST(DeviceCounts, CharpysFramesAfterTheBreakStayWithinTheirLaunchesAndWaits) {
  const SceneDescription scene = sceneNamed("charpy", 8000);
  const Simulation sim(scene, loadSceneMesh(scene));
  const DeviceFrameCost c = deviceFrameCost(sim, "Charpy after the break (8k, converged)", 40);
  EXPECT_LE(c.kernels, 18.6);
  EXPECT_LE(c.barriers, 1948.0);
  EXPECT_LE(c.syncs, 6.6) << "the issue's target after the break: 8";
}

// The CPU backend has no device: its rows are zero.
TEST(DeviceCounts, TheCpuBackendReportsNone) {
  const auto sim = hangingSphere();
  CpuStepBackend cpu(sim->model());
  SimState state = sim->state();
  const StepReport r = cpu.step(state, sim->settings());
  EXPECT_EQ(r.launches, 0);
  EXPECT_EQ(r.syncs, 0);
  EXPECT_EQ(r.hostToDeviceBytes, 0.0);
}

}  // namespace
}  // namespace galsculpt

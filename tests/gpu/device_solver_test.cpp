// The device backend's frame (gpu/device_solver.h) run by the host executor against the CPU
// backend, frame by frame: the kernels, gathers, multigrid, line search, contact, plasticity
// and fracture the GPU runs, checked on machines without one. Scenes are the paper's, smaller.
#include "gpu/device_solver.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "engine/scene.h"
#include "engine/scene_mesh.h"
#include "engine/simulation.h"
#include "gpu/host_executor.h"
#include "solver/knife.h"

namespace galsculpt::gpu {
namespace {

namespace fs = std::filesystem;

SceneDescription sceneNamed(const std::string& name, int tets) {
  SceneDescription s =
      loadScene(fs::path(GALSCULPT_SOURCE_DIR) / "assets" / "scenes" / (name + ".json"));
  s.mesh.tets = tets;
  return s;
}

struct Comparison {
  double maxRelativeError = 0.0;  // largest |x_dev - x_cpu| over the largest displacement
  int cpuDamaged = 0, deviceDamaged = 0;
  int frames = 0;
};

// Runs `frames` frames on both backends from the same state; positions are compared after
// every frame, relative to the largest displacement from the start.
Comparison compare(const Simulation& sim, int frames, StepSettings settings = {}) {
  if (settings.gridHandles.empty() || !settings.multigrid) settings = sim.settings();
  SimState cpu = sim.state();
  cpu.workspace = nullptr;
  SimState device = sim.state();
  device.workspace = nullptr;
  HostExecutor ex;
  DeviceSolver<HostExecutor> solver(ex, sim.model());
  Comparison c;
  const std::vector<Vec3> start = cpu.x;
  for (int f = 0; f < frames; ++f) {
    const StepReport rc = step(sim.model(), cpu, settings);
    const StepReport rd = solver.step(device, settings);
    EXPECT_EQ(rc.retries, rd.retries) << "frame " << f;
    double displacement = 1e-12, error = 0.0;
    for (size_t v = 0; v < cpu.x.size(); ++v) {
      displacement = std::max(displacement, (cpu.x[v] - start[v]).norm());
      error = std::max(error, (cpu.x[v] - device.x[v]).norm());
      EXPECT_TRUE(device.x[v].allFinite());
    }
    c.maxRelativeError = std::max(c.maxRelativeError, error / displacement);
    EXPECT_NEAR(cpu.time, device.time, 1e-12);
    ++c.frames;
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

TEST(DeviceSolver, HangingSphereMatchesTheCpuFor100Frames) {
  const SceneDescription scene = sceneNamed("hanging_sphere", 6000);
  const Simulation sim(scene, loadSceneMesh(scene));
  const Comparison c = compare(sim, 100);
  EXPECT_LT(c.maxRelativeError, 1e-6) << "double precision on both sides";
}

}  // namespace
}  // namespace galsculpt::gpu

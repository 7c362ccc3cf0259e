// The CUDA backend against the CPU backend on the GPU itself: the hanging sphere, a cut sphere
// and the Charpy bar for 100 frames each. Skipped, saying why, where no usable GPU exists (the
// same frames run on the host executor in gpu_host_tests everywhere).
#include <gtest/gtest.h>

#include "gpu/cuda_step_backend.h"
#include "tests/gpu/backend_comparison.h"

namespace galsculpt::gpu {
namespace {

std::unique_ptr<StepBackend> cudaBackend(const Simulation& sim, std::string& reason) {
  return makeCudaStepBackend(sim.model(), sim.settings(), reason);
}

void expectTheGpuSolvesAsTheCpuDoes(const Simulation& sim, int frames) {
  std::string reason;
  auto device = cudaBackend(sim, reason);
  if (!device) GTEST_SKIP() << "no usable GPU: " << reason;
  expectSolvesAsTheCpuDoes(sim, *device, frames);
}

TEST(CudaBackend, HangingSphereSolvesAsOnTheCpuFor100Frames) {
  expectTheGpuSolvesAsTheCpuDoes(*hangingSphere(), 100);
}

TEST(CudaBackend, CutSphereSolvesAsOnTheCpuFor100Frames) {
  expectTheGpuSolvesAsTheCpuDoes(*cutSphere(), 100);
}

TEST(CudaBackend, SplitSphereSolvesAsOnTheCpuFor100Frames) {
  expectTheGpuSolvesAsTheCpuDoes(*splitSphere(), 100);
}

// The paper's fixed work (one linearized step, one V-cycle) with fracture: the same equations
// on both sides, compared directly.
TEST(CudaBackend, CharpyBarMatchesTheCpuFor100Frames) {
  SceneDescription scene = withPaperSolver(sceneNamed("charpy", 8000));
  scene.fracture.threshold = 1.0e9;
  // What these frames cover: non-local fracture (the scene's own is local) at fixed thresholds.
  scene.fracture.kernelRadius = 0.0005;
  scene.fracture.energy = 0.0;
  const Simulation sim(scene, loadSceneMesh(scene));
  std::string reason;
  auto backend = cudaBackend(sim, reason);
  if (!backend) GTEST_SKIP() << "no usable GPU: " << reason;
  const Comparison c = compareWithCpu(sim, *backend, 100);
  EXPECT_LT(c.maxRelativeError, 1e-3);
  EXPECT_GT(c.cpuDamaged, 100);
  EXPECT_NEAR(c.deviceDamaged, c.cpuDamaged, 0.01 * c.cpuDamaged);
}

}  // namespace
}  // namespace galsculpt::gpu

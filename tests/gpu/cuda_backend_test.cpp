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

// Tolerances: the GPU runs the same double-precision arithmetic in another order (fused
// multiply-adds, tree reductions), so elastic scenes agree to round-off grown over 100 frames;
// fracture amplifies it (see the host-executor test), hence the wider bound there.
TEST(CudaBackend, HangingSphereMatchesTheCpuFor100Frames) {
  const SceneDescription scene = sceneNamed("hanging_sphere", 6000);
  const Simulation sim(scene, loadSceneMesh(scene));
  std::string reason;
  auto backend = cudaBackend(sim, reason);
  if (!backend) GTEST_SKIP() << "no usable GPU: " << reason;
  EXPECT_LT(compareWithCpu(sim, *backend, 100).maxRelativeError, 1e-6);
}

TEST(CudaBackend, CutSphereMatchesTheCpuFor100Frames) {
  const SceneDescription scene = sceneNamed("hanging_sphere", 6000);
  Simulation sim(scene, loadSceneMesh(scene));
  sim.cut(sweptBladeSurface(Vec3(-1, 0.01, -1), Vec3(-1, 0.01, 1), Vec3(1, 0.01, -1),
                            Vec3(1, 0.01, 1)));
  sim.cut(sweptBladeSurface(Vec3(-1, -0.085, -1), Vec3(-1, -0.085, 1), Vec3(1, -0.085, -1),
                            Vec3(1, -0.085, 1)));
  std::string reason;
  auto backend = cudaBackend(sim, reason);
  if (!backend) GTEST_SKIP() << "no usable GPU: " << reason;
  EXPECT_LT(compareWithCpu(sim, *backend, 100).maxRelativeError, 1e-6);
}

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

// The frame's device paths, run on the CPU (DeviceLikeExecutor): the same scenes as the CUDA
// backend's tests, everywhere, so that a defect of those paths shows without a GPU.
#include <gtest/gtest.h>

#include "solver/frame/frame_solver.h"
#include "tests/gpu/backend_comparison.h"
#include "tests/gpu/device_like_executor.h"

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

}  // namespace
}  // namespace galsculpt

#include "engine/session/backend_select.h"

#include <gtest/gtest.h>

#include "gpu/cuda_step_backend.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

SimModel smallModel() {
  return buildSimModel(
      test::gridBar(1, 2, 1, 0.1),
      {MaterialModel::StableNeoHookean, lameFromYoungPoisson(1e5, 0.4), 1000.0, {}});
}

StepSettings multigridSettings() {
  StepSettings s;
  s.type = SolverType::Multigrid;
  s.gridHandles = {4};
  return s;
}

TEST(BackendSelect, CpuIsTakenAsAskedWithoutANote) {
  const SimModel m = smallModel();
  const BackendChoice c = chooseBackend(BackendRequest::Cpu, m, multigridSettings());
  EXPECT_EQ(c.backend->name(), "cpu");
  EXPECT_TRUE(c.note.empty());
}

// device-like: the GPU's paths on the CPU, for the multigrid (the reference's direct solve has no
// device path: it runs on the CPU and says so).
TEST(BackendSelect, DeviceLikeRunsTheMultigridOrSaysWhyNot) {
  const SimModel m = smallModel();
  const BackendChoice c = chooseBackend(BackendRequest::DeviceLike, m, multigridSettings());
  EXPECT_EQ(c.backend->name(), "device-like");
  EXPECT_TRUE(c.backend->offloads());
  EXPECT_TRUE(c.note.empty());
  const BackendChoice reference = chooseBackend(BackendRequest::DeviceLike, m, StepSettings{});
  EXPECT_EQ(reference.backend->name(), "cpu");
  EXPECT_NE(reference.note.find("multigrid only"), std::string::npos) << reference.note;
}

// Where the CUDA backend cannot run (no GPU here, or a build without nvcc), auto and cuda both
// fall back to the CPU; cuda, asked for, says why as a note, auto keeps the reason apart (the
// user did not ask for a GPU); where it can, they take it.
TEST(BackendSelect, AutoAndCudaTakeTheGpuOrSayWhyNot) {
  const SimModel m = smallModel();
  std::string reason;
  const bool gpu = gpu::makeCudaStepBackend(m, multigridSettings(), reason) != nullptr;
  for (BackendRequest requested : {BackendRequest::Auto, BackendRequest::Cuda}) {
    const BackendChoice c = chooseBackend(requested, m, multigridSettings());
    if (gpu) {
      EXPECT_EQ(c.backend->name(), "cuda");
      EXPECT_TRUE(c.note.empty());
      EXPECT_TRUE(c.fallback.empty());
    } else {
      EXPECT_EQ(c.backend->name(), "cpu");
      const std::string& why = requested == BackendRequest::Cuda ? c.note : c.fallback;
      EXPECT_TRUE((requested == BackendRequest::Cuda ? c.fallback : c.note).empty());
      EXPECT_NE(why.find(reason), std::string::npos) << why;
      EXPECT_NE(why.find("running on the CPU"), std::string::npos) << why;
      if (!gpu::cudaBackendBuilt()) {
        EXPECT_NE(why.find("no CUDA backend"), std::string::npos) << why;
      }
    }
  }
}

TEST(BackendSelect, TheReferenceSolverStaysOnTheCpuAndSaysSo) {
  const SimModel m = smallModel();
  StepSettings reference;  // multigrid off: the direct sparse Cholesky
  const BackendChoice c = chooseBackend(BackendRequest::Cuda, m, reference);
  EXPECT_EQ(c.backend->name(), "cpu");
  EXPECT_NE(c.note.find("reference solver"), std::string::npos) << c.note;
}

TEST(BackendSelect, TheCpuBackendRunsTheSolversFrame) {
  const SimModel m = smallModel();
  const BackendChoice c = chooseBackend(BackendRequest::Cpu, m, multigridSettings());
  SimState a = initialState(m), b = initialState(m);
  c.backend->step(a, multigridSettings());
  step(m, b, multigridSettings());
  for (int v = 0; v < m.numVertices(); ++v) EXPECT_EQ(a.x[v], b.x[v]);
  EXPECT_GT(a.time, 0.0);
}

}  // namespace
}  // namespace galsculpt

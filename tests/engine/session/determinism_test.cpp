// Determinism pinned, as Box2D's determinism test: the hash of positions, damage and blade
// crossings after a fixed run, at one and at two threads, against literals. Every reduction sums
// in a fixed order, so the thread count must not change a bit. A change that alters results on
// purpose updates the literals knowingly (and says so in its commit); one that alters them by
// accident fails here.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>

#include "engine/scene/scene_mesh.h"
#include "engine/session/playback.h"
#include "engine/session/simulation.h"
#include "solver/frame/parallel.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

namespace fs = std::filesystem;

const fs::path kAssets = fs::path(GALSCULPT_SOURCE_DIR) / "assets";

std::uint64_t hashState(const SimState& s) {
  std::uint64_t hash = 1469598103934665603ull;  // FNV-1a
  auto mix = [&hash](const void* data, size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < bytes; ++i) hash = (hash ^ p[i]) * 1099511628211ull;
  };
  mix(s.x.data(), s.x.size() * sizeof(Vec3));
  mix(s.damaged.data(), s.damaged.size());
  mix(s.crossing.data(), s.crossing.size() * sizeof(float));
  return hash;
}

std::string hex(std::uint64_t h) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "0x%016llx", static_cast<unsigned long long>(h));
  return buffer;
}

// The committed ball (1.5k vertices) as rubber hanging from its top under gravity, 30 frames on
// the scene's multigrid, on the CPU backend.
std::uint64_t hangingBall() {
  test::TempDir dir;
  test::writeText(dir / "hanging.json",
                  "{\"name\": \"hanging ball\", \"mesh\": {\"file\": \"" +
                      (kAssets / "meshes" / "sphere_small.node").string() +
                      "\"}, \"material\": {\"preset\": \"rubber\"}, \"gravity\": [0, -9.81, 0], "
                      "\"anchors\": [{\"box\": {\"min\": [-1, 0.085, -1]}}], "
                      "\"solver\": {\"type\": \"multigrid\", \"grid\": \"50/all\", "
                      "\"backend\": \"cpu\"}}");
  const SceneDescription scene = loadScene(dir / "hanging.json");
  Simulation sim(scene, loadSceneMesh(scene));
  for (int f = 0; f < 30; ++f) sim.advance();
  return hashState(sim.state());
}

// The default clay ball cut through by a knife stroke over ten frames (the stroke of
// assets/scripts/sphere_cut.json, written here so that editing the demo does not move the pin),
// 60 frames.
std::uint64_t sphereCut() {
  test::TempDir dir;
  test::writeText(dir / "cut.json",
                  "{\"scene\": \"" + (kAssets / "scenes" / "default.json").string() +
                      "\", \"frames\": 60, \"events\": [{\"frame\": 5, \"tool\": \"knife\", "
                      "\"duration\": 10, \"from\": [[-0.2, 0.2, 0.02], [0.2, 0.2, 0.02]], "
                      "\"to\": [[-0.2, -0.2, 0.02], [0.2, -0.2, 0.02]]}]}");
  PlaybackScript script = loadPlaybackScript(dir / "cut.json");
  script.scene.solver.backend = BackendRequest::Cpu;
  Simulation sim(script.scene, loadSceneMesh(script.scene));
  Playback playback(script, sim);
  while (!playback.finished()) playback.advance();
  return hashState(sim.state());
}

// Pinned on 2026-11-30 (x86-64, GCC 12, Release). Changed knowingly when the CPU backend became
// the one frame on the CPU executor (solver/frame/frame_solver.h): the same arithmetic in
// another order (per-element stiffness gathered per block, symmetric from its upper blocks), a
// round-off change of about 1e-13 of the motion (docs/benchmarks.md). Changed knowingly again
// when frames became converged by default (Newton with multigrid-preconditioned CG to the
// residual tolerance, anchored rows out of the coarse levels, the C1 closed-crack band, the knife
// cutting all it has swept): different, converged results, not round-off. And again when
// Newton started from the predicted positions x_n + h v_n and the fine smoother read a
// single-precision copy of the operator: converged to the same tolerance from another start.
// The sphere cut again when Newton's step test read the full step (not a shortened one) and
// the line search quadratic interpolation: other iterates within the same tolerance. The
// sphere cut again when the converged preset kept element stiffnesses within a sub-step
// (stiffness_tolerance 1e-3): other Newton matrices in its later iterations, the same tolerance.
// The sphere cut again when cracks opened one way (a damaged element's energy the least over its
// crack openings, solver/fem/element_kernels.h): another energy for the cut elements.
// The sphere cut again when the host factored a coarsest level of more than 64 handles sparse
// (solver/multigrid/coarse_cholesky.h; the cut splits the ball's 50 handles into more): the
// same coarse solve in another order, round-off.
// Both again when a chord step that did not halve the residual ended the sub-step's chord steps
// (solver/frame/frame_solver.h, substep) and a null Newton step was taken rather than refused by
// round-off: other iterates within the same tolerance.
// The sphere cut again when a damaged element's strain stiffness was formed as
// lambda a a^T + S^T W S, its Hessian assembled through per-vertex sums, and an element with every
// crack open returned exact zeros (solver/fem/element_kernels.h): the same energy in another
// order of round-off.
// The sphere cut again when no chord step followed a step that switched the cracks of more than
// 64 elements, and a shortened step was lengthened again while the potential kept falling
// (frame_solver.h): other iterates within the same tolerance. The uncut ball takes neither.
// Both again when PCG's V-cycle kept the coarsest level's factorization while its matrix stayed
// within 1 % of the one factored (solver/multigrid/multigrid_cycle.h, kCoarseReuse): another
// preconditioner, the same tolerance; and the sphere cut when a damaged element's openings came
// from one elimination of the opened edges (element_kernels.h, eliminateEdges): round-off.
// The sphere cut again when the coarsest level's sparse factor went by 12x12 blocks
// (solver/multigrid/coarse_cholesky.cpp): the same coarse solve in another order, round-off.
// The sphere cut again when a sub-step converged only with each piece within the tolerance of
// its own loads (StepSettings::convergePieces, frame_solver.h): its halves solved further.
// The sphere cut again when a crack closed only past a strain of -5e-11 (kCrackClosingStrain,
// element_kernels.h: ties at rest no longer decided by round-off) and a piece whose start would
// press on a held one kept the straight line (accelerated_start.h).
// The sphere cut again when the clay preset became stable neo-Hookean (engine/scene/scene.cpp):
// another material, not round-off. Again when it became Hencky with its flow in the energy
// (materials/hencky.h): another material. Again when an iteration after the first solved only
// the region where the residual was (StepSettings::localNewton, local_region.h): other iterates
// within the same tolerance.
// Both again when the host factored every coarsest level by 12x12 blocks, not only those of
// more than 64 handles (solver/multigrid/coarse_cholesky.h): the same coarse solve in another
// order, round-off.
// Both again when a stiffness block summed its elements' terms in element order, not colour
// order (SimModel::blockSlots, stiffness_gather.h), and the Galerkin refresh summed each finer
// row's blocks before taking them into the row's modes (multigrid_cycle.h): round-off.
// The sphere cut again when a scene's crack faces closed by the smooth law of width 0.01 by
// default (fracture.crack_width, solver/fem/crack_law.h): another law at the crack faces, not
// round-off. The uncut ball has no crack.
constexpr std::uint64_t kHangingBall = 0x4e74d4d3ef752236;
constexpr std::uint64_t kSphereCut = 0x8c4df9b95b0f24d3;

TEST(Determinism, PinnedHashesAtOneAndTwoThreads) {
  const int threads = threadCount();
  for (int n : {1, 2}) {
    setThreadCount(n);
    const std::uint64_t hanging = hangingBall();
    const std::uint64_t cut = sphereCut();
    EXPECT_EQ(hex(hanging), hex(kHangingBall)) << "hanging ball, " << n << " thread(s)";
    EXPECT_EQ(hex(cut), hex(kSphereCut)) << "sphere cut, " << n << " thread(s)";
  }
  setThreadCount(threads);
}

}  // namespace
}  // namespace galsculpt

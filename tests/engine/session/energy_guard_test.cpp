// The vertex energy guard (scene solver.energy_guard "vertex", StepSettings::vertexGuard()): when
// a Newton step raises the incremental potential, shorten the steps of the vertices whose share
// rose instead of the whole step. Judged where steps overshoot: the paper preset's one
// linearized step on StVK clay under grabs that jerk a patch of the surface 2-3 cm in two frames
// and let go (the shaping brushes hold by springs and no longer make steps overshoot).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "engine/scene/scene_mesh.h"
#include "engine/session/playback.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

namespace fs = std::filesystem;

std::vector<FrameMetrics> playJerks(EnergyGuard guard, int frames) {
  test::TempDir dir;
  std::string events;
  for (int k = 0, f = 2; f < frames; ++k, f += 4)
    events += std::string(events.empty() ? "" : ",") + "{\"frame\": " + std::to_string(f) +
              ", \"tool\": \"brush\", \"center\": [" + (k % 2 ? "0.05" : "0") +
              ", 0.1, 0], \"radius\": 0.03, \"offset\": [0, " + (k % 2 ? "-0.02" : "0.03") +
              ", 0], \"duration\": 2}";
  test::writeText(
      dir / "jerks.json",
      "{\"scene\": \"" +
          (fs::path(GALSCULPT_SOURCE_DIR) / "assets" / "scenes" / "default.json").string() +
          "\", \"frames\": " + std::to_string(frames) + ", \"events\": [" + events + "]}");
  PlaybackScript script = loadPlaybackScript(dir / "jerks.json");
  script.scene.material.model = MaterialModel::StVK;
  const SolverOptions shipped = script.scene.solver;
  script.scene.solver = solverPreset(SolverPreset::Paper);
  script.scene.solver.grid = shipped.grid;
  script.scene.solver.energyGuard = guard;
  Simulation sim(script.scene, loadSceneMesh(script.scene));
  Playback playback(script, sim);
  std::vector<FrameMetrics> out;
  while (!playback.finished()) out.push_back(playback.advance());
  return out;
}

// 40 frames of the clay ball jerked by ten grabs. The vertex guard evaluates a fraction of the
// elements for each shortening (less than half the whole-body passes of backing off the whole
// step), and the clay stays whole: its volume within 0.5 % of the whole-step guard's, nothing
// diverges.
TEST(EnergyGuard, ShortensOnlyTheStepsOfTheVerticesWhoseEnergyRose) {
  const int frames = 40;
  const std::vector<FrameMetrics> body = playJerks(EnergyGuard::Body, frames);
  const std::vector<FrameMetrics> vertex = playJerks(EnergyGuard::Vertex, frames);
  double bodyPasses = 0.0, vertexPasses = 0.0;
  int shortenedFrames = 0;
  for (int f = 0; f < frames; ++f) {
    bodyPasses += body[f].energyPasses;
    vertexPasses += vertex[f].energyPasses;
    shortenedFrames += body[f].backtracks > 0 ? 1 : 0;
    EXPECT_LT(std::abs(vertex[f].volumeChangePct), std::abs(body[f].volumeChangePct) + 0.5)
        << "the clay's volume as the whole-step guard keeps it; frame " << f;
    EXPECT_TRUE(std::isfinite(vertex[f].residual)) << "frame " << f;
    EXPECT_LE(vertex[f].energyPasses, vertex[f].backtracks + 1e-12)
        << "a guard round is at most a whole pass; frame " << f;
  }
  EXPECT_GE(shortenedFrames, 10) << "the grabs make the full step overshoot";
  EXPECT_LT(vertexPasses, 0.5 * bodyPasses);
  EXPECT_EQ(vertex.back().pieces, 1);
}

}  // namespace
}  // namespace galsculpt

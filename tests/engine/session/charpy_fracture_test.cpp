// The Charpy scene at full size (labelled `slow`): the rigid pendulum starts a crack at the notch
// root and breaks the bar in two under a laboratory-sized load, losing the energy the bar took;
// gravity alone breaks nothing.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <algorithm>
#include <map>
#include <numeric>

#include "engine/scene/scene.h"
#include "engine/scene/scene_mesh.h"
#include "engine/session/simulation.h"
#include "engine/surface/surface_io.h"
#include "solver/mesh/surface_checks.h"
#include "solver/mesh/union_find.h"
#include "tests/surface_expectations.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

namespace fs = std::filesystem;

struct CharpyRun {
  int damaged = 0;
  std::vector<int> pieceSizes;      // largest first
  Vec3 firstDamage = Vec3::Zero();  // mean rest midpoint of the first frame's broken edges
  double peakLoad = 0.0, opening = 0.0;
  double absorbed = 0.0;    // J, the pendulum's energy lost (metrics)
  double work = 0.0;        // J, the load's work along the striker's path, frame by frame
  int invertedPieces = 0;   // the most over the frames
  int surfaceProblems = 0;  // frames (every 25th and the last) whose surface was not closed
  int exportedPieces = 0;   // surface pieces of the final OBJ, read back
  bool exportClosed = false;
  int exportCrossings = 0;  // crossing face pairs in the final OBJ, read back
  int pieces = 0;           // the run's piece count
  std::string exportSummary;
};

// `tets`: the scene's mesh at this size instead (0: as the scene says).
CharpyRun runCharpy(bool pendulum, int frames, const char* sceneFile = "charpy.json",
                    int tets = 0) {
  const fs::path cache = fs::path(GALSCULPT_SOURCE_DIR) / "build" / "test-cache";
  if (!getenv("GALSCULPT_CACHE_DIR")) setenv("GALSCULPT_CACHE_DIR", cache.c_str(), 1);
  SceneDescription scene =
      loadScene(fs::path(GALSCULPT_SOURCE_DIR) / "assets" / "scenes" / sceneFile);
  if (tets > 0) scene.mesh.tets = tets;
  if (!pendulum) {
    scene.colliders.pop_back();  // the striker
    scene.measure.loadCollider = -1;
  }
  const TetMesh mesh = loadSceneMesh(scene);
  Simulation sim(scene, mesh);
  CharpyRun run;
  double lastDisplacement = 0.0;
  for (int f = 0; f < frames; ++f) {
    const FrameMetrics m = sim.advance();
    // No frame may fail and be halved.
    EXPECT_EQ(m.retries, 0) << "frame " << m.frame;
    run.peakLoad = std::max(run.peakLoad, m.loadN);
    run.work += m.loadN * (m.strikerDisplacementM - lastDisplacement);
    lastDisplacement = m.strikerDisplacementM;
    run.absorbed = m.absorbedEnergyJ;
    run.invertedPieces = std::max(run.invertedPieces, m.invertedPieces);
    run.opening = m.openingM;
    if (run.damaged == 0 && m.damagedEdges > 0) {
      const SimModel& model = sim.model();
      for (int e = 0; e < model.numEdges(); ++e) {
        if (!sim.state().damaged[e]) continue;
        run.firstDamage +=
            0.5 * (model.mesh.vertices[model.edges[e][0]] + model.mesh.vertices[model.edges[e][1]]);
      }
      run.firstDamage /= m.damagedEdges;
    }
    run.damaged = m.damagedEdges;
    if (m.frame % 25 == 0 || m.frame == frames) {
      const SurfaceTopology topo = analyzeSurface(sim.surface().mesh);
      if (!topo.closedManifold()) {
        ++run.surfaceProblems;
        ADD_FAILURE() << "frame " << m.frame << ": " << topo.describeProblem();
      }
    }
  }
  test::TempDir dir;
  const ExportedSurface exported = sim.exportSurface();
  run.exportSummary = exported.summary();
  run.pieces = sim.pieceStats().pieces;
  writeVisualSurface(dir / "final.obj", exported.surface);
  const TriMesh back = test::readObjByIndex((dir / "final.obj").string());
  run.exportClosed = analyzeSurface(back).closedManifold();
  run.exportedPieces = countSurfacePieces(back);
  run.exportCrossings = static_cast<int>(findSelfIntersections(back, 1000).size());
  for (const Vec3& x : sim.state().x) EXPECT_TRUE(x.allFinite());
  const SimModel& model = sim.model();
  UnionFind pieces(model.numVertices());
  for (int e = 0; e < model.numEdges(); ++e) {
    if (!sim.state().damaged[e]) pieces.unite(model.edges[e][0], model.edges[e][1]);
  }
  std::map<int, int> sizes;
  for (int v = 0; v < model.numVertices(); ++v) ++sizes[pieces.find(v)];
  for (const auto& [root, size] : sizes) run.pieceSizes.push_back(size);
  std::sort(run.pieceSizes.rbegin(), run.pieceSizes.rend());
  return run;
}

// The net-section estimate of docs/benchmarks.md: P = 2/3 sigma_f B b^2 / S for the scene's
// 2 GPa, B = 10 mm, b = 8 mm under the notch, S = 40 mm.
constexpr double kNetSectionLoad = 2.0 / 3.0 * 2.0e9 * 0.010 * 0.008 * 0.008 / 0.040;

TEST(CharpyFracture, ThePendulumBreaksTheBarInTwoFromTheNotchAndGravityAloneDoesNot) {
  // 300 frames (3 ms): the halves part at frame ~31 and the load is 0 from frame ~36; until
  // sections cracked through parted (docs/physics.md, fracture pass item 8) a hinge of a few
  // edges under the striker held them together until frame ~258 (docs/benchmarks.md). By frame
  // 300 the halves have swung and their broken ends fold where the crack band is rough: what
  // the export is made for.
  const CharpyRun struck = runCharpy(true, 300);
  ASSERT_GT(struck.damaged, 0);
  // The notch root is at x = 27.5 mm, y = 8 mm (the notch is 2 mm deep in the 10 mm top face).
  EXPECT_NEAR(struck.firstDamage.x(), 0.0275, 0.002);
  EXPECT_NEAR(struck.firstDamage.y(), 0.008, 0.002);
  // A laboratory Charpy load (measured 28.2 kN), not what keeps a kinematic hammer on its path
  // (1.1 MN), and what the pendulum lost is the load's work along its path (measured 17.1 J of
  // its 297 J: a brittle break; the hammer swings on).
  EXPECT_GT(struck.peakLoad, 0.5 * kNetSectionLoad);
  EXPECT_LT(struck.peakLoad, 2.0 * kNetSectionLoad);
  EXPECT_GT(struck.absorbed, 5.0);
  EXPECT_LT(struck.absorbed, 60.0);
  EXPECT_NEAR(struck.work, struck.absorbed, 0.05 * struck.absorbed)
      << "the hammer's lost energy is the work its load did";
  EXPECT_GT(struck.opening, 0.0) << "the notch mouth opens";
  // Two halves, each with over 40 % of the vertices; what else broke off is crushed debris
  // under the striker.
  ASSERT_GE(struck.pieceSizes.size(), 2u);
  const int total = std::accumulate(struck.pieceSizes.begin(), struck.pieceSizes.end(), 0);
  EXPECT_GT(struck.pieceSizes[0], 0.4 * total);
  EXPECT_GT(struck.pieceSizes[1], 0.4 * total);
  if (struck.pieceSizes.size() > 2) {
    EXPECT_LT(struck.pieceSizes[2], 0.01 * total);
  }
  EXPECT_EQ(struck.invertedPieces, 0) << "no piece turned inside out at any frame";
  // The exported surface, as indexed in the file: one closed shell per piece, nothing crossing
  // (docs/surface.md, "What an export promises").
  EXPECT_EQ(struck.surfaceProblems, 0);
  EXPECT_TRUE(struck.exportClosed) << struck.exportSummary;
  EXPECT_EQ(struck.exportedPieces, struck.pieces) << struck.exportSummary;
  EXPECT_EQ(struck.exportCrossings, 0) << struck.exportSummary;
  const CharpyRun resting = runCharpy(false, 40);
  EXPECT_EQ(resting.damaged, 0);
  EXPECT_LT(std::abs(resting.opening), 1e-6);
}

// The scene's fracture energy on a local stress makes its breaking load the material's, not the
// mesh's: the peak moves 1.0 % from 28k to 56k tets (docs/benchmarks.md), where a fixed threshold
// moved 19.6 % on a local stress and 6.5 % over the 0.5 mm kernel the scene had before, and the
// energy with that kernel 24.7 %. The peak comes at frame ~23 on both meshes.
TEST(CharpyFracture, ThePeakLoadHoldsWhenTheMeshIsRefinedTwice) {
  const CharpyRun coarse = runCharpy(true, 30);
  const CharpyRun fine = runCharpy(true, 30, "charpy.json", 56000);
  ASSERT_GT(coarse.peakLoad, 0.5 * kNetSectionLoad);
  EXPECT_NEAR(fine.peakLoad, coarse.peakLoad, 0.05 * coarse.peakLoad);
  EXPECT_EQ(fine.invertedPieces, 0);
}

// The ductile steel (charpy_ductile.json: yields at 355 MPa, tears at 15 % edge strain) takes
// the same pendulum: a crack starts at the notch root only after the bar has bent, and the bar
// absorbs an upper-shelf energy, many times the brittle bar's, bending until it slips through
// the anvils (measured on 28k tets with the anvils' 1 mm radius: 23.6 kN peak, 147.1 J, first
// edge at frame 91, the load gone by frame 181; the brittle bar: 28.2 kN, 17.1 J). With the
// stress criterion the ductile bar broke after little flow and absorbed 11.1 J, less than the
// brittle one.
TEST(CharpyFracture, TheDuctileBarBendsAndAbsorbsManyTimesTheBrittleBarsEnergy) {
  const CharpyRun bent = runCharpy(true, 220, "charpy_ductile.json");
  ASSERT_GT(bent.damaged, 0) << "a crack starts";
  EXPECT_NEAR(bent.firstDamage.x(), 0.0275, 0.002);
  EXPECT_NEAR(bent.firstDamage.y(), 0.008, 0.002);
  EXPECT_GT(bent.peakLoad, 5e3);
  EXPECT_LT(bent.peakLoad, 60e3);
  EXPECT_GT(bent.absorbed, 100.0) << "an upper-shelf energy: the brittle bar absorbs 18 J";
  EXPECT_LT(bent.absorbed, 297.0) << "no more than the pendulum had";
  EXPECT_NEAR(bent.work, bent.absorbed, 0.05 * bent.absorbed)
      << "the hammer's lost energy is the work its load did";
  EXPECT_EQ(bent.invertedPieces, 0);
  EXPECT_EQ(bent.surfaceProblems, 0);
  EXPECT_TRUE(bent.exportClosed);
}

}  // namespace
}  // namespace galsculpt

#include "engine/surface/export_surface.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include "engine/session/simulation.h"
#include "engine/surface/surface_io.h"
#include "solver/fracture/knife.h"
#include "solver/io/input_error.h"
#include "solver/mesh/surface_checks.h"
#include "tests/engine/session/clay_ball.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

namespace fs = std::filesystem;

// Per shell of `mesh`: its enclosed volume.
std::vector<double> shellVolumes(const TriMesh& mesh) {
  std::vector<int> shellOfFace;
  const int shells = countSurfacePieces(mesh, &shellOfFace);
  return enclosedVolumes(mesh, shellOfFace, shells);
}

// What an export promises (docs/surface.md): one closed, outward shell per piece, nothing
// crossing, no two vertices at one position (a reader that welds keeps them apart).
void expectWhole(const TriMesh& mesh, int pieces) {
  const SurfaceTopology topo = analyzeSurface(mesh);
  EXPECT_TRUE(topo.closedManifold()) << topo.describeProblem();
  const std::vector<double> volumes = shellVolumes(mesh);
  EXPECT_EQ(static_cast<int>(volumes.size()), pieces);
  for (double v : volumes) EXPECT_GT(v, 0.0);
  EXPECT_TRUE(findSelfIntersections(mesh, 10).empty());
  std::map<std::array<double, 3>, int> at;
  for (const Vec3& p : mesh.vertices) ++at[{p.x(), p.y(), p.z()}];
  for (const auto& [p, count] : at) EXPECT_EQ(count, 1) << p[0] << ' ' << p[1] << ' ' << p[2];
}

// The clay ball cut through by a plane 2 cm above its centre and left a frame to settle: the
// two halves touch along the cut, where the visualization surface places each side by its own
// fitted deformation and the two cross (sphere_cut.json right after its knife).
struct CutBall {
  Simulation sim{test::clayBall().scene, test::clayBall().mesh};
  CutBall() {
    const int cut = sim.cut(sweptBladeSurface(Vec3(-0.2, 0.2, 0.02), Vec3(0.2, 0.2, 0.02),
                                              Vec3(-0.2, -0.2, 0.02), Vec3(0.2, -0.2, 0.02)));
    EXPECT_GT(cut, 0);
    for (int f = 0; f < 2; ++f) sim.advance();
  }
};

TEST(ExportSurface, TheHalvesOfACutBallAreTwoClosedShellsThatDoNotCross) {
  CutBall ball;
  ASSERT_EQ(ball.sim.pieceStats().pieces, 2);
  const ExportedSurface exported = ball.sim.exportSurface();
  EXPECT_EQ(exported.pieces, 2);
  EXPECT_EQ(exported.crossings, 0);
  EXPECT_EQ(exported.invertedShells, 0);
  expectWhole(exported.surface.mesh, 2);
  EXPECT_NE(exported.summary().find("2 piece(s), closed"), std::string::npos) << exported.summary();

  // Written and read back (the reader welds equal positions): still whole.
  test::TempDir dir;
  for (const char* name : {"cut.obj", "cut.stl", "cut.ply", "cut.glb"}) {
    writeVisualSurface(dir / name, exported.surface);
    expectWhole(readSurface(dir / name), 2);
  }
}

TEST(ExportSurface, WithoutTheCheckAndPullTheCutBallsSidesCross) {
  // The separation and its check are what clear the crossings: with neither, the same state
  // crosses (the case the export exists for).
  CutBall ball;
  const VisualSurface& all = ball.sim.surface();
  std::vector<int> piece(ball.sim.model().numVertices());
  for (int v = 0; v < ball.sim.model().numVertices(); ++v) piece[v] = ball.sim.pieceOf(v);
  SurfaceExportOptions none;
  none.separation = 0.0;
  none.rounds = 0;
  const std::vector<Vec3> centres(all.mesh.vertices);  // nothing moves
  const ExportedSurface raw = makeExportSurface(all, centres, piece, none);
  EXPECT_GT(raw.contacts, 0);
  EXPECT_EQ(raw.crossings, 0) << "the faces that cross are of the two halves";
}

// The mean edge length of `model`'s rest mesh.
double meanEdge(const SimModel& model) {
  double sum = 0.0;
  for (const auto& [a, b] : model.edges)
    sum += (model.mesh.vertices[a] - model.mesh.vertices[b]).norm();
  return sum / model.numEdges();
}

// `sim` with the vertices `moved` picks shifted by `shift`.
template <class Pick>
void shiftVertices(Simulation& sim, const Vec3& shift, Pick moved) {
  SimulationSnapshot s = sim.snapshot();
  for (int v = 0; v < sim.model().numVertices(); ++v)
    if (moved(v)) s.x[v] += shift;
  sim.restore(s);
}

// The clay ball with a knife half way across it (one piece, an open notch) and the vertices of
// the notch's upper lip that `inFlap` picks slid an edge along the cut and pushed a third of an
// edge down into the lower lip (the slit is opened, not sealed): the piece folds through itself
// where the lips overlap, which no pull of crack-side copies can clear.
template <class Pick>
ExportedSurface exportFoldedNotch(Pick inFlap) {
  Simulation sim(test::clayBall().scene, test::clayBall().mesh);
  EXPECT_GT(sim.cut(sweptBladeSurface(Vec3(-0.2, 0.2, 0.02), Vec3(0.0, 0.2, 0.02),
                                      Vec3(-0.2, -0.2, 0.02), Vec3(0.0, -0.2, 0.02))),
            0);
  EXPECT_EQ(sim.pieceStats().pieces, 1);
  const double h = meanEdge(sim.model());
  const std::vector<Vec3>& X = sim.model().mesh.vertices;
  shiftVertices(sim, Vec3(h, 0, -h / 3.0),
                [&](int v) { return X[v].z() > 0.02 && inFlap(X[v], h); });
  return sim.exportSurface();
}

TEST(ExportSurface, FoldedFacesOfOnePieceAreCarvedOutAndTheirVolumeReported) {
  // A flap of the lip folded: the export carves the corners of the crossing cells out of the
  // piece and says what it left out.
  const ExportedSurface exported = exportFoldedNotch(
      [](const Vec3& p, double h) { return p.x() < -4.0 * h && std::abs(p.y()) < h; });
  EXPECT_EQ(exported.crossings, 0);
  EXPECT_EQ(exported.contacts, 0);
  EXPECT_FALSE(exported.carveBudgetReached);
  EXPECT_GT(exported.carvedCorners, 0);
  EXPECT_GT(exported.detachedShells, 0);
  EXPECT_GT(exported.detachedVolume, 0.0);
  EXPECT_LT(exported.detachedVolume, kExportCarveBudget * exported.volume) << exported.summary();
  EXPECT_NEAR(exported.volume, shellVolumes(exported.surface.mesh)[0], 1e-12);
  expectWhole(exported.surface.mesh, 1);
  EXPECT_NE(exported.summary().find("corner(s) carved out where crack faces crossed"),
            std::string::npos)
      << exported.summary();
}

TEST(ExportSurface, AFoldTooLargeToCarveIsRemadeAsTheRegionItEncloses) {
  // The whole lip folded: carving it out would leave out more than the budget, so the piece is
  // remade as the boundary of the region its faces wind around (solidify.h): closed, nothing
  // crossing, its material kept, and said.
  const ExportedSurface exported =
      exportFoldedNotch([](const Vec3& p, double h) { return p.x() < -2.0 * h; });
  EXPECT_EQ(exported.crossings, 0);
  EXPECT_EQ(exported.contacts, 0);
  EXPECT_EQ(exported.carvedCorners, 0);
  EXPECT_EQ(exported.solidifiedPieces, 1);
  expectWhole(exported.surface.mesh, 1);
  // The material kept: the ball less what the lip overlaps where it was pushed into the lower
  // one (the grid's rounding changes the folded shell's volume by far less than 1 %).
  EXPECT_GT(exported.volume, 0.9 * totalVolume(test::clayBall().mesh)) << exported.summary();
  EXPECT_LT(std::abs(exported.solidifiedVolumeChange), 0.01 * exported.volume);
  EXPECT_NE(exported.summary().find("1 piece(s), closed"), std::string::npos) << exported.summary();
  EXPECT_NE(exported.summary().find("folded piece(s) remade as the boundary of the region"),
            std::string::npos)
      << exported.summary();
}

TEST(ExportSurface, PiecesThatOverlapAreReportedAsContactAndNotCarved) {
  // The cut ball's upper half pushed a third of an edge into the lower one: two closed shells
  // that cross each other. The simulation let the pieces overlap; the export says so and keeps
  // their material.
  CutBall ball;
  const SimModel& model = ball.sim.model();
  const int upper = ball.sim.pieceOf(static_cast<int>(
      std::max_element(model.mesh.vertices.begin(), model.mesh.vertices.end(),
                       [](const Vec3& p, const Vec3& q) { return p.z() < q.z(); }) -
      model.mesh.vertices.begin()));
  shiftVertices(ball.sim, Vec3(0, 0, -meanEdge(model) / 3.0),
                [&](int v) { return ball.sim.pieceOf(v) == upper; });
  const ExportedSurface exported = ball.sim.exportSurface();
  EXPECT_EQ(exported.crossings, 0);
  EXPECT_GT(exported.contacts, 0);
  EXPECT_EQ(exported.carvedCorners, 0);
  EXPECT_EQ(exported.detachedShells, 0);
  EXPECT_TRUE(analyzeSurface(exported.surface.mesh).closedManifold());
  EXPECT_EQ(shellVolumes(exported.surface.mesh).size(), 2u);
  EXPECT_NE(exported.summary().find("pieces overlap"), std::string::npos) << exported.summary();
}

TEST(ExportSurface, AnInternalSlitIsACavityShellThatTheExportLeavesOut) {
  Simulation sim(test::clayBall().scene, test::clayBall().mesh);
  // An edge none of whose tets touches the boundary: damaged, it is a slit inside the ball.
  const SimModel& model = sim.model();
  std::vector<char> onBoundary(model.numVertices(), 0);
  for (const Tri& f : boundaryFaces(model.mesh))
    for (int v : f) onBoundary[v] = 1;
  int inner = -1;
  for (int e = 0; e < model.numEdges() && inner < 0; ++e)
    if (!onBoundary[model.edges[e][0]] && !onBoundary[model.edges[e][1]]) inner = e;
  ASSERT_GE(inner, 0);
  SimulationSnapshot s = sim.snapshot();
  s.damaged[inner] = 1;
  sim.restore(s);
  ASSERT_EQ(sim.pieceStats().pieces, 1);
  EXPECT_EQ(shellVolumes(sim.surface().mesh).size(), 2u) << "the ball and its slit";

  // Closed (at rest), the slit is sealed.
  const ExportedSurface sealed = sim.exportSurface();
  EXPECT_EQ(sealed.sealedEdges, 1);
  EXPECT_EQ(sealed.droppedShells, 0);
  expectWhole(sealed.surface.mesh, 1);

  // Not sealed, its cavity shell is left out and counted.
  std::vector<int> piece(model.numVertices(), 0);
  const ExportedSurface dropped =
      makeExportSurface(sim.surface(), std::vector<Vec3>(sim.surface().mesh.vertices), piece);
  EXPECT_EQ(dropped.droppedShells, 1);
  EXPECT_LT(dropped.droppedVolume, 1e-9);
  expectWhole(dropped.surface.mesh, 1);
}

TEST(ExportSurface, PiecesThatMeetAtAPointKeepTheirOwnVertexThere) {
  // Two tetrahedra, pieces of their own, with a corner at one position: a reader that welds
  // equal positions would join them there into a point where two sheets touch.
  VisualSurface two;
  const std::vector<Vec3> corners{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  for (int piece = 0; piece < 2; ++piece) {
    const int base = two.mesh.numVertices();
    for (const Vec3& c : corners) two.mesh.vertices.push_back(piece == 0 ? c : Vec3(-c));
    for (const Tri& f : {Tri{0, 2, 1}, Tri{0, 1, 3}, Tri{0, 3, 2}, Tri{1, 2, 3}}) {
      // The second, mirrored through the shared corner, keeps its faces outward reversed.
      if (piece == 0) two.mesh.faces.push_back({base + f[0], base + f[1], base + f[2]});
      if (piece == 1) two.mesh.faces.push_back({base + f[0], base + f[2], base + f[1]});
      two.tags.push_back(SurfaceTag::Outer);
      two.cellVertex.push_back(piece);
    }
  }
  ASSERT_EQ(two.mesh.vertices[0], two.mesh.vertices[4]);
  const ExportedSurface exported =
      makeExportSurface(two, std::vector<Vec3>(two.mesh.vertices), {0, 1});
  EXPECT_EQ(exported.pieces, 2);
  expectWhole(exported.surface.mesh, 2);
  // Only the second copy stepped, and by a little.
  EXPECT_EQ(exported.surface.mesh.vertices[0], Vec3(0, 0, 0));
  EXPECT_GT(exported.surface.mesh.vertices[4].norm(), 0.0);
  EXPECT_LT(exported.surface.mesh.vertices[4].norm(), 0.01);
}

TEST(ExportSurface, FacesOfPiecesNumberedNegativeAreLeftOut) {
  CutBall ball;
  const VisualSurface& all = ball.sim.surface();
  std::vector<int> piece(ball.sim.model().numVertices());
  for (int v = 0; v < ball.sim.model().numVertices(); ++v)
    piece[v] = ball.sim.pieceOf(v) == 0 ? 0 : -1;
  const ExportedSurface one = makeExportSurface(all, std::vector<Vec3>(all.mesh.vertices), piece);
  EXPECT_EQ(one.pieces, 1);
  for (int v : one.surface.cellVertex) EXPECT_EQ(ball.sim.pieceOf(v), 0);
  EXPECT_EQ(shellVolumes(one.surface.mesh).size(), 1u);
}

TEST(ExportSurface, ATetMeshWrittenWithItsDamageReopensCracked) {
  CutBall ball;
  test::TempDir dir;
  ball.sim.writeTetsWithDamage(dir / "cut");
  SceneDescription scene = test::clayBall().scene;
  scene.mesh = MeshSource{};
  scene.mesh.kind = MeshSource::Kind::File;
  scene.mesh.path = dir / "cut.node";
  const TetMesh mesh = loadSceneMesh(scene);
  Simulation reopened(scene, mesh);
  EXPECT_EQ(reopened.state().damaged, ball.sim.state().damaged);
  EXPECT_EQ(reopened.pieceStats().pieces, 2);
  expectWhole(reopened.exportSurface().surface.mesh, 2);

  // A .damage of another write is refused, naming it.
  const fs::path other = dir / "other";
  ball.sim.writeTetsWithDamage(other);
  fs::copy_file(dir / "other.damage", dir / "cut.damage", fs::copy_options::overwrite_existing);
  try {
    Simulation mixed(scene, mesh);
    ADD_FAILURE() << "a damage file of another write was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cut.damage"), std::string::npos) << e.what();
  }
}

TEST(ExportSurface, ATetPartedAndCrushedFlatIsLeftOutOfTheTetExportThatReopens) {
  // A tet parted between the two halves carries nothing between them and may be crushed flat
  // as they move; the reader refuses a zero-volume tet, so the export leaves it out.
  CutBall ball;
  const SimModel& model = ball.sim.model();
  int parted = -1;
  for (int t = 0; t < model.numTets() && parted < 0; ++t) {
    const Tet& tet = model.mesh.tets[t];
    if (ball.sim.pieceOf(tet[0]) != ball.sim.pieceOf(tet[3])) parted = t;
  }
  ASSERT_GE(parted, 0);
  const Tet tet = model.mesh.tets[parted];
  SimulationSnapshot crushed = ball.sim.snapshot();
  const Vec3 a = crushed.x[tet[0]], b = crushed.x[tet[1]], c = crushed.x[tet[2]];
  const Vec3 normal = (b - a).cross(c - a).normalized();
  crushed.x[tet[3]] -= normal.dot(crushed.x[tet[3]] - a) * normal;  // onto the other three's plane
  ball.sim.restore(crushed);
  ASSERT_TRUE(
      isFlatTet(crushed.x[tet[0]], crushed.x[tet[1]], crushed.x[tet[2]], crushed.x[tet[3]]));

  test::TempDir dir;
  const int leftOut = ball.sim.writeTetsWithDamage(dir / "cut");
  EXPECT_GE(leftOut, 1);
  SceneDescription scene = test::clayBall().scene;
  scene.mesh = MeshSource{};
  scene.mesh.kind = MeshSource::Kind::File;
  scene.mesh.path = dir / "cut.node";
  const TetMesh mesh = loadSceneMesh(scene);
  EXPECT_EQ(mesh.numTets(), model.numTets() - leftOut);
  Simulation reopened(scene, mesh);
  EXPECT_EQ(reopened.pieceStats().pieces, 2);
  EXPECT_GT(std::count(reopened.state().damaged.begin(), reopened.state().damaged.end(), 1), 0);
  expectWhole(reopened.exportSurface().surface.mesh, 2);
}

}  // namespace
}  // namespace galsculpt

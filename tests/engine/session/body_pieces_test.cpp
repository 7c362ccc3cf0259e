#include "engine/session/body_pieces.h"

#include <gtest/gtest.h>

#include "tests/test_util.h"

namespace galsculpt {
namespace {

// A bar of 4 cubes along x, cut across its third cube (x = 0.25): the tets of that cube part,
// leaving whole tets of two cubes on one side and of one cube on the other (debris under a
// fraction of 0.3).
struct CutBar {
  SimModel model = buildSimModel(test::gridBar(4, 1, 1, 0.1), MaterialParams{});
  SimState state = initialState(model);
  CutBar() {
    for (int e = 0; e < model.numEdges(); ++e) {
      const double a = model.mesh.vertices[model.edges[e][0]].x();
      const double b = model.mesh.vertices[model.edges[e][1]].x();
      if ((a < 0.25) != (b < 0.25)) state.damaged[e] = 1;
    }
    ++state.damageRevision;
  }
  int vertexAt(double x) const {
    for (int v = 0; v < model.numVertices(); ++v)
      if (std::abs(model.mesh.vertices[v].x() - x) < 1e-12) return v;
    return -1;
  }
};

TEST(BodyPieces, CountsPiecesDebrisAndTheVolumesOfWholeTets) {
  CutBar bar;
  BodyPieces pieces(0.3, false);
  pieces.update(bar.model, bar.state);
  EXPECT_EQ(pieces.count(), 2);
  EXPECT_NE(pieces.of(bar.vertexAt(0.0)), pieces.of(bar.vertexAt(0.4)));
  EXPECT_EQ(pieces.debrisPieces(), 1);
  EXPECT_FALSE(pieces.removed(bar.vertexAt(0.4))) << "debris is kept";
  EXPECT_FALSE(pieces.removesSome());
  // Every tet of the cut cube has corners on both sides and is not counted.
  double body = 0.0, whole = 0.0;
  for (int t = 0; t < bar.model.numTets(); ++t) {
    body += bar.model.rest[t].volume;
    bool inside = true;
    for (int v : bar.model.mesh.tets[t])
      inside = inside && pieces.of(v) == pieces.of(bar.model.mesh.tets[t][0]);
    if (inside) whole += bar.model.rest[t].volume;
    EXPECT_EQ(pieces.counted(t), inside) << "tet " << t;
  }
  EXPECT_NEAR(pieces.restVolume(), whole, 1e-15);
  EXPECT_NEAR(pieces.restVolume(), 0.75 * body, 1e-15) << "three cubes of four";
  EXPECT_NEAR(pieces.currentVolume(bar.model, bar.state.x), whole, 1e-15);
  // A piece's rest volume is its vertices' corner cells': the last cube and half the cut one
  // (each Kuhn tet of the cut cube has two corners on each side).
  EXPECT_NEAR(pieces.debrisVolumePercent(), 37.5, 1e-9);
  double mass = 0.0;
  for (int v = 0; v < bar.model.numVertices(); ++v)
    if (pieces.of(v) == pieces.of(bar.vertexAt(0.4))) mass += bar.model.mass[v];
  EXPECT_NEAR(pieces.debrisMassKg(), mass, 1e-15);
}

TEST(BodyPieces, RemovedDebrisLeavesTheSurfaceAndIsNoPieceToLookAt) {
  CutBar bar;
  BodyPieces pieces(0.3, true);
  pieces.update(bar.model, bar.state);
  ASSERT_TRUE(pieces.removesSome());
  EXPECT_TRUE(pieces.removed(bar.vertexAt(0.4)));
  SurfaceBuilder builder(bar.model);
  builder.update(bar.model, bar.state);
  const VisualSurface& all = builder.surface();
  const VisualSurface shown = pieces.withoutRemoved(all);
  ASSERT_GT(shown.mesh.numFaces(), 0);
  EXPECT_LT(shown.mesh.numFaces(), all.mesh.numFaces());
  for (int f = 0; f < shown.mesh.numFaces(); ++f) EXPECT_FALSE(pieces.removed(shown.cellVertex[f]));
  EXPECT_EQ(pieces.invertedPieces(all), 0);
  // Mirrored through the cut, the kept piece encloses negative volume; the removed one is not
  // looked at.
  SimState mirrored = bar.state;
  for (int v = 0; v < bar.model.numVertices(); ++v) mirrored.x[v].x() = -mirrored.x[v].x();
  builder.update(bar.model, mirrored);
  EXPECT_EQ(pieces.invertedPieces(builder.surface()), 1);
  BodyPieces kept(0.3, false);
  kept.update(bar.model, bar.state);
  EXPECT_EQ(kept.invertedPieces(builder.surface()), 2);
}

TEST(BodyPieces, CountsAgainOnlyWhenTheDamageRevisionChanges) {
  CutBar bar;
  BodyPieces pieces(0.3, false);
  pieces.update(bar.model, bar.state);
  std::fill(bar.state.damaged.begin(), bar.state.damaged.end(), 0);
  pieces.update(bar.model, bar.state);
  EXPECT_EQ(pieces.count(), 2) << "the same revision is the same damage";
  ++bar.state.damageRevision;
  pieces.update(bar.model, bar.state);
  EXPECT_EQ(pieces.count(), 1);
  EXPECT_EQ(pieces.debrisPieces(), 0);
}

}  // namespace
}  // namespace galsculpt

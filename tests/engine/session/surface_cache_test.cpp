#include "engine/session/surface_cache.h"

#include <gtest/gtest.h>

#include "tests/test_util.h"

namespace galsculpt {
namespace {

// The surface is built on the first call for a state, reused for the same frame and damage,
// and built again after a new frame, a new damage revision or an invalidation.
TEST(SurfaceCache, BuildsOncePerStateWhoeverAsks) {
  const SimModel model = buildSimModel(test::gridBar(2, 1, 1, 0.1), MaterialParams{});
  SimState state = initialState(model);
  BodyPieces pieces(0.01, false);
  pieces.update(model, state);
  SurfaceCache cache(model);
  SurfaceUpdateStats stats;
  const VisualSurface& first = cache.get(model, state, 0, pieces, &stats);
  EXPECT_GT(stats.msTopology + stats.msPositions + stats.rebuiltOwners, 0.0) << "built";
  const int faces = first.mesh.numFaces();
  EXPECT_EQ(faces, 2 * 2 * (2 + 1 + 2));  // a 2x1x1 box: 10 unit squares of two triangles
  state.x[0].x() -= 0.05;                 // moved without a frame: not seen until invalidated
  const VisualSurface& again = cache.get(model, state, 0, pieces, &stats);
  EXPECT_EQ(&again, &first);
  EXPECT_EQ(stats.rebuiltOwners, 0);
  EXPECT_EQ(stats.msPositions, 0.0);
  EXPECT_EQ(cache.builder().surface().mesh.vertices, first.mesh.vertices);
  cache.invalidate();
  const VisualSurface& moved = cache.get(model, state, 0, pieces, &stats);
  EXPECT_GT(stats.msPositions, 0.0);
  bool found = false;
  for (const Vec3& p : moved.mesh.vertices) found = found || p.isApprox(state.x[0]);
  EXPECT_TRUE(found) << "the moved corner is on the surface";
  EXPECT_GT(cache.lastUpdate().msPositions, 0.0) << "the last update's cost, for bench";
  cache.get(model, state, 1, pieces, &stats);
  EXPECT_GT(stats.msPositions, 0.0) << "a new frame";
}

// With the debris rule removing a piece, the surface shown leaves its faces out.
TEST(SurfaceCache, ShowsTheSurfaceWithoutRemovedDebris) {
  const SimModel model = buildSimModel(test::gridBar(4, 1, 1, 0.1), MaterialParams{});
  SimState state = initialState(model);
  for (int e = 0; e < model.numEdges(); ++e) {
    const double a = model.mesh.vertices[model.edges[e][0]].x();
    const double b = model.mesh.vertices[model.edges[e][1]].x();
    if ((a < 0.25) != (b < 0.25)) state.damaged[e] = 1;
  }
  ++state.damageRevision;
  BodyPieces pieces(0.3, true);
  pieces.update(model, state);
  SurfaceCache cache(model);
  const VisualSurface& shown = cache.get(model, state, 0, pieces);
  EXPECT_LT(shown.mesh.numFaces(), cache.builder().surface().mesh.numFaces());
  for (int f = 0; f < shown.mesh.numFaces(); ++f) EXPECT_FALSE(pieces.removed(shown.cellVertex[f]));
}

}  // namespace
}  // namespace galsculpt

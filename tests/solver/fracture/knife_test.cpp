#include "solver/fracture/knife.h"

#include <gtest/gtest.h>

#include <random>

#include "solver/frame/step.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

const BladeTriangle kUnit{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};  // normal +z

TEST(Knife, SegmentTriangleCases) {
  EXPECT_TRUE(segmentCrossesTriangle(Vec3(0.2, 0.2, 1), Vec3(0.2, 0.2, -1), kUnit)) << "interior";
  EXPECT_FALSE(segmentCrossesTriangle(Vec3(0.8, 0.8, 1), Vec3(0.8, 0.8, -1), kUnit)) << "misses";
  EXPECT_FALSE(segmentCrossesTriangle(Vec3(0.2, 0.2, 1), Vec3(0.2, 0.2, 0.5), kUnit))
      << "same side";
  EXPECT_TRUE(segmentCrossesTriangle(Vec3(0, 0, 1), Vec3(0, 0, -1), kUnit)) << "through a corner";
  EXPECT_TRUE(segmentCrossesTriangle(Vec3(0.5, 0.5, 1), Vec3(0.5, 0.5, -1), kUnit))
      << "through the hypotenuse";
  EXPECT_TRUE(segmentCrossesTriangle(Vec3(0.5, 0, -1), Vec3(0.5, 0, 1), kUnit))
      << "through an edge, from below";
  EXPECT_FALSE(segmentCrossesTriangle(Vec3(0.1, 0.1, 0), Vec3(0.5, 0.2, 0), kUnit))
      << "lying in the blade";
  EXPECT_FALSE(segmentCrossesTriangle(Vec3(-1, 0.1, 0), Vec3(2, 0.1, 0), kUnit))
      << "in the plane, across the blade";
  // An end on the blade counts on the positive side: cut only when the other end is below.
  EXPECT_TRUE(segmentCrossesTriangle(Vec3(0.2, 0.2, 0), Vec3(0.2, 0.3, -1), kUnit));
  EXPECT_FALSE(segmentCrossesTriangle(Vec3(0.2, 0.2, 0), Vec3(0.2, 0.3, 1), kUnit));
  const BladeTriangle degenerate{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)};
  EXPECT_FALSE(segmentCrossesTriangle(Vec3(0.5, 0, 1), Vec3(0.5, 0, -1), degenerate))
      << "a blade that sweeps no area cuts nothing";
  // Grazing by one ulp either way.
  const double tiny = std::nextafter(0.0, 1.0);
  EXPECT_TRUE(segmentCrossesTriangle(Vec3(1.0, tiny, 1), Vec3(1.0, tiny, -1),
                                     {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 2, 0)}));
  EXPECT_FALSE(segmentCrossesTriangle(Vec3(1.0, -tiny, 1), Vec3(1.0, -tiny, -1),
                                      {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 2, 0)}));
}

struct Bar {
  SimModel model;
  SimState state;
};

Bar makeBar() {
  Bar b{
      buildSimModel(test::gridBar(2, 8, 2, 0.1),
                    {MaterialModel::StableNeoHookean, lameFromYoungPoisson(1e5, 0.4), 1000.0, {}}),
      {}};
  b.state = initialState(b.model);
  return b;
}

// A blade across the whole bar at height y, moving from one side to the other.
std::vector<BladeTriangle> planarCut(double y) {
  return sweptBladeSurface(Vec3(-1, y, -1), Vec3(-1, y, 2), Vec3(2, y, -1), Vec3(2, y, 2));
}

TEST(Knife, APlanarCutThroughVerticesGivesExactlyTwoPieces) {
  Bar b = makeBar();
  // y = 0.4 holds a layer of mesh vertices: each joins the upper side, none is left alone.
  const int cut = cutAlongSurface(b.model, b.state, planarCut(0.4));
  EXPECT_GT(cut, 0);
  EXPECT_EQ(countDamagePieces(b.model, b.state), 2);
  EXPECT_EQ(b.state.damageRevision, 1u);
  EXPECT_EQ(cutAlongSurface(b.model, b.state, planarCut(0.4)), 0) << "damage is for good";
  EXPECT_EQ(b.state.damageRevision, 1u);
}

TEST(Knife, CrossingFractionIsWhereTheEdgeMeetsTheBladePlane) {
  EXPECT_DOUBLE_EQ(crossingFraction(Vec3(0.2, 0.2, 1), Vec3(0.2, 0.2, -3), kUnit), 0.25);
  EXPECT_DOUBLE_EQ(crossingFraction(Vec3(0.2, 0.2, -1), Vec3(0.2, 0.2, 1), kUnit), 0.5);
  // Ends on the plane are kept off the vertex.
  EXPECT_DOUBLE_EQ(crossingFraction(Vec3(0.2, 0.2, 0), Vec3(0.2, 0.3, -1), kUnit), kCrossingMargin);
  EXPECT_DOUBLE_EQ(crossingFraction(Vec3(0.2, 0.2, 1), Vec3(0.2, 0.3, 0), kUnit),
                   1.0 - kCrossingMargin);
}

TEST(Knife, ACutRecordsWhereTheBladeCrossedEachEdge) {
  Bar b = makeBar();
  ASSERT_EQ(b.state.crossing, std::vector<float>(b.model.numEdges(), kNoCrossing));
  // Oblique plane through no vertex: every crossing lies on it (float precision).
  const Vec3 normal = Vec3(0.2, 1.0, 0.3).normalized();
  const Vec3 center(0.1, 0.43, 0.1);
  const Vec3 t1 = normal.unitOrthogonal(), t2 = normal.cross(t1);
  const int cut =
      cutAlongSurface(b.model, b.state,
                      sweptBladeSurface(center - 3 * t1 - 3 * t2, center + 3 * t1 - 3 * t2,
                                        center - 3 * t1 + 3 * t2, center + 3 * t1 + 3 * t2));
  ASSERT_GT(cut, 0);
  int crossed = 0;
  for (int e = 0; e < b.model.numEdges(); ++e) {
    ASSERT_EQ(b.state.damaged[e] != 0, hasCrossing(b.state.crossing[e])) << e;
    if (!b.state.damaged[e]) continue;
    const Vec3& p = b.state.x[b.model.edges[e][0]];
    const Vec3& q = b.state.x[b.model.edges[e][1]];
    const Vec3 at = p + static_cast<double>(b.state.crossing[e]) * (q - p);
    // On the plane, or kept the margin away from a vertex next to it.
    const float f = b.state.crossing[e];
    const bool atMargin =
        f == static_cast<float>(kCrossingMargin) || f == static_cast<float>(1.0 - kCrossingMargin);
    EXPECT_LT(std::abs(normal.dot(at - center)),
              (atMargin ? kCrossingMargin + 1e-6 : 1e-6) * (q - p).norm())
        << e;
    ++crossed;
  }
  EXPECT_EQ(crossed, cut);
  // Damage is for good, and so is where it was cut: a second blade leaves the crossings.
  const std::vector<float> first = b.state.crossing;
  cutAlongSurface(b.model, b.state, planarCut(0.43));
  for (int e = 0; e < b.model.numEdges(); ++e) {
    if (hasCrossing(first[e])) {
      EXPECT_EQ(b.state.crossing[e], first[e]) << e;
    }
  }
  // Through a layer of vertices (y = 0.4): crossings at the margin, next to the vertex.
  Bar layer = makeBar();
  cutAlongSurface(layer.model, layer.state, planarCut(0.4));
  for (int e = 0; e < layer.model.numEdges(); ++e) {
    if (!layer.state.damaged[e]) continue;
    const float at = layer.state.crossing[e];
    EXPECT_TRUE(std::abs(at - kCrossingMargin) < 1e-7 ||
                std::abs(at - (1 - kCrossingMargin)) < 1e-7)
        << at;
  }
}

TEST(Knife, APartialCutLeavesASlitAndAnObliqueStrokeSevers) {
  Bar b = makeBar();
  // The blade reaches half way through the bar's depth: a slit, still one piece.
  const int slit = cutAlongSurface(b.model, b.state,
                                   sweptBladeSurface(Vec3(-1, 0.43, -1), Vec3(-1, 0.43, 0.1),
                                                     Vec3(2, 0.43, -1), Vec3(2, 0.43, 0.1)));
  EXPECT_GT(slit, 0);
  EXPECT_EQ(countDamagePieces(b.model, b.state), 1);
  // An oblique screen stroke extruded along parallel view rays cuts through.
  const std::vector<Vec3> nearPoints = {Vec3(-1, 0.2, -1), Vec3(0.1, 0.3, -1), Vec3(2, 0.5, -1)};
  std::vector<Vec3> farPoints;
  for (const Vec3& p : nearPoints) farPoints.push_back(p + Vec3(0, 0, 3));
  EXPECT_GT(cutAlongSurface(b.model, b.state, extrudedStrokeSurface(nearPoints, farPoints)), 0);
  EXPECT_EQ(countDamagePieces(b.model, b.state), 2);
}

std::vector<int> anchorTop(const SimModel& m) {
  std::vector<int> top;
  for (int v = 0; v < m.numVertices(); ++v) {
    if (m.mesh.vertices[v].y() > 0.8 - 1e-9) top.push_back(v);
  }
  return top;
}

// The two halves of a cut bar: the upper one hangs from its anchor, the lower one falls
// freely (backward Euler is exact for a free rigid body), under the reference and under the
// multigrid (one linearized step per frame, three V-cycles), which agree on the falling half only
// when the multigrid's aggregates are split along the cut.
TEST(Knife, CutHalvesMoveIndependentlyUnderReferenceAndMultigrid) {
  auto run = [](bool multigrid, bool split) {
    Bar b = makeBar();
    cutAlongSurface(b.model, b.state, planarCut(0.4));
    StepSettings s;
    b.state.anchors.push_back({anchorTop(b.model), {}, {}, {}});
    s.type = multigrid ? SolverType::Multigrid : SolverType::Reference;
    s.gridHandles = {12};
    s.splitAggregates = split;
    s.cycles = 3;
    s.coarseSolver = CoarseSolver::Cholesky;
    if (!multigrid) s = referenceSettings(s);
    for (int f = 0; f < 10; ++f) {
      const StepReport r = step(b.model, b.state, s);
      EXPECT_EQ(r.retries, 0);
    }
    return b;
  };
  const Bar reference = run(false, true);
  const Bar split = run(true, true);
  const Bar glued = run(true, false);
  const double h = 1.0 / 60.0;
  // Free fall under backward Euler: after n steps y drops by g h^2 n (n + 1) / 2.
  const double drop = 9.81 * h * h * 10 * 11 / 2.0;
  double maxSplit = 0.0, maxGlued = 0.0;
  for (int v = 0; v < reference.model.numVertices(); ++v) {
    const Vec3& rest = reference.model.mesh.vertices[v];
    if (rest.y() > 0.4 - 1e-9) continue;
    EXPECT_NEAR(reference.state.x[v].y(), rest.y() - drop, 1e-6 * drop) << "lower half falls";
    EXPECT_NEAR((reference.state.x[v] - rest).head<1>().norm(), 0.0, 1e-9);
    maxSplit = std::max(maxSplit, (split.state.x[v] - reference.state.x[v]).norm());
    maxGlued = std::max(maxGlued, (glued.state.x[v] - reference.state.x[v]).norm());
  }
  EXPECT_LT(maxSplit, 1e-3 * drop) << "crack-aware multigrid matches the reference";
  EXPECT_GT(maxGlued, 10 * maxSplit) << "aggregates across the cut glue the halves";
  std::cout << "cut halves after 10 frames, largest distance to the reference: split " << maxSplit
            << " m, glued " << maxGlued << " m (drop " << drop << " m)\n";
}

// Fifty random planar cuts through a hanging bar: no NaN, no failed solve, damage only grows.
TEST(Knife, FiftyRandomCutsStayFiniteAndSolvable) {
  Bar b = makeBar();
  StepSettings s;
  b.state.anchors.push_back({anchorTop(b.model), {}, {}, {}});
  s.type = SolverType::Multigrid;
  s.gridHandles = {12};
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int previous = 0;
  for (int c = 0; c < 50; ++c) {
    const Vec3 center = Vec3(0.1, 0.4, 0.1) + Vec3(0.1 * u(rng), 0.4 * u(rng), 0.1 * u(rng));
    const Vec3 normal = Vec3(u(rng), u(rng), u(rng)).normalized();
    const Vec3 t1 = normal.unitOrthogonal(), t2 = normal.cross(t1);
    const double r = 0.05 + 0.2 * (u(rng) + 1.0);
    cutAlongSurface(b.model, b.state,
                    sweptBladeSurface(center - r * t1 - r * t2, center + r * t1 - r * t2,
                                      center - r * t1 + r * t2, center + r * t1 + r * t2));
    const StepReport rep = step(b.model, b.state, s);
    EXPECT_EQ(rep.retries, 0) << "cut " << c;
    for (const Vec3& x : b.state.x) ASSERT_TRUE(x.allFinite()) << "cut " << c;
    int damaged = 0;
    for (auto d : b.state.damaged) damaged += d;
    EXPECT_GE(damaged, previous);
    previous = damaged;
  }
  EXPECT_GT(countDamagePieces(b.model, b.state), 2);
}

}  // namespace
}  // namespace galsculpt

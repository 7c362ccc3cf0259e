#include "solver/multigrid/fragment_correction.h"

#include <gtest/gtest.h>

#include "tests/solver/multigrid/multigrid_fixture.h"

namespace galsculpt {
namespace {

using test::Cycle;
using test::elasticitySystem;
using test::System;

// Slices cut off the top of a bar of elasticitySystem(3, 200, 3): 90 cuts between vertex
// layers, every second one (many small fragments side by side).
std::vector<std::uint8_t> slicedTop(const System& s) {
  std::vector<std::uint8_t> damaged(s.model.numEdges(), 0);
  for (int e = 0; e < s.model.numEdges(); ++e) {
    const double y0 = s.model.mesh.vertices[s.model.edges[e][0]].y();
    const double y1 = s.model.mesh.vertices[s.model.edges[e][1]].y();
    for (int cut = 0; cut < 90; ++cut) {
      const double y = 0.3 + 0.04 * cut + 0.01;
      if ((y0 - y) * (y1 - y) < 0.0) damaged[e] = 1;
    }
  }
  return damaged;
}

// Slices cut off the top of a bar (small fragments, no coarse handle), then one slice crumbled
// into loose vertices: the handles do not change, yet the fragments do. They follow the damage,
// the same as a hierarchy that saw the final damage at once (a frame depends on the damage, not
// on the order it came in: kept from before, a fresh solver, a reopened project's, ran on
// differently from the one that had stepped through the damage).
TEST(Multigrid, FragmentsFollowTheDamageWhereTheHandlesDoNot) {
  const System s = elasticitySystem(3, 200, 3);
  const std::vector<std::uint8_t> sliced = slicedTop(s);
  std::vector<std::uint8_t> crumbled = sliced;
  for (int e = 0; e < s.model.numEdges(); ++e) {
    const double y0 = s.model.mesh.vertices[s.model.edges[e][0]].y();
    if (y0 > 0.31 && y0 < 0.35) crumbled[e] = 1;  // every edge of the first slice
  }
  Multigrid stepwise(s.model.pattern, s.model.mesh.vertices, s.model.edges, {20});
  ASSERT_TRUE(stepwise.updateDamage(s.model.edges, sliced, 1));
  const size_t slicedFragments = stepwise.fragmentStart().size() - 1;
  const int handles = stepwise.level(0).handles;
  EXPECT_TRUE(stepwise.updateDamage(s.model.edges, crumbled, 2)) << "the fragments changed";
  EXPECT_EQ(stepwise.level(0).handles, handles) << "(the handles did not)";
  Multigrid atOnce(s.model.pattern, s.model.mesh.vertices, s.model.edges, {20});
  ASSERT_TRUE(atOnce.updateDamage(s.model.edges, crumbled, 1));
  EXPECT_EQ(atOnce.fragmentStart().size() - 1, slicedFragments - 1) << "one slice is gone";
  EXPECT_EQ(stepwise.fragmentStart(), atOnce.fragmentStart());
  EXPECT_EQ(stepwise.fragmentVertices(), atOnce.fragmentVertices());
}

// Many small fragments next to each other (slices cut off the top of a bar): their corrections
// run in parallel, and each reads its neighbours' positions, so they must not depend on which
// thread moved a neighbour first. The same solve with 1 and 2 threads, bit for bit (an app
// session replayed headless differed in its last bits before).
TEST(Multigrid, FragmentCorrectionsDoNotDependOnTheThreadCount) {
  const System s = elasticitySystem(3, 200, 3);
  Multigrid mg(s.model.pattern, s.model.mesh.vertices, s.model.edges, {20});
  const std::vector<std::uint8_t> damaged = slicedTop(s);
  ASSERT_TRUE(mg.updateDamage(s.model.edges, damaged, 1));
  ASSERT_GE(mg.fragmentStart().size(), 80u) << "many fragments, more than a thread's chunk";
  const int threads = threadCount();
  setThreadCount(1);
  Cycle c(s, mg);
  Eigen::VectorXd serial;
  c.solve(serial, Cycle::settings());
  setThreadCount(2);
  for (int run = 0; run < 20; ++run) {
    Eigen::VectorXd parallel;
    c.solve(parallel, Cycle::settings());
    EXPECT_TRUE(parallel == serial) << "run " << run << ": " << (parallel - serial).norm();
  }
  setThreadCount(threads);
}

}  // namespace
}  // namespace galsculpt

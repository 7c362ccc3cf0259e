// The held vertices (solver/frame/held_vertices.h): anchors on their paths at the sub-step's end,
// removed debris held where the state has it (an anchor's path winning over it).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "solver/fracture/debris.h"
#include "solver/frame/cpu_executor.h"
#include "solver/frame/held_vertices.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

MaterialParams rubber() {
  return {MaterialModel::StableNeoHookean, lameFromYoungPoisson(1e5, 0.45), 1000.0, {}};
}

// A bar whose debris (pieces under a fifth of it) is removed, and its held vertices.
struct DebrisBar {
  SimModel m = withDebrisRemoval(buildSimModel(test::gridBar(8, 2, 2, 0.01), rubber()));
  SimState s = initialState(m);
  CpuExecutor ex;
  FrameData<CpuExecutor> d{m};
  HeldVertexSet<CpuExecutor> held{ex, m, d};
  static SimModel withDebrisRemoval(SimModel model) {
    model.debrisRemoval = 0.2;
    return model;
  }
};

TEST(HeldVertexSet, AnchorsFollowTheirPathsAndDebrisStaysWhereTheStateHasIt) {
  DebrisBar bar;
  SimModel& m = bar.m;
  SimState& s = bar.s;
  FrameData<CpuExecutor>& d = bar.d;
  HeldVertexSet<CpuExecutor>& held = bar.held;
  // A slab of 9 vertices cut off at x = 0.005: debris (under a fifth of the body).
  cutAt(m, s, 0.005);
  held.updateRemovedDebris(censusPieces(m, s.damaged));
  for (int v = 0; v < m.numVertices(); ++v)
    if (m.mesh.vertices[v].x() < 0.005) s.x[v] += Vec3(0, -0.003, 0);  // where it fell
  held.holdRemovedAt(s);
  AnchorConstraint anchor;
  anchor.vertices = {m.numVertices() - 1, 0};  // vertex 0 is debris too: the path wins
  anchor.path = {{0.0, Vec3::Zero()}, {1.0, Vec3(0, 0, 0.01)}};
  held.prepare({anchor}, 0.5);
  std::vector<double> x(3 * m.numVertices(), 0.0);
  d.x.upload(x);
  held.place();
  d.x.download(x.data(), x.size());
  std::vector<std::uint8_t> fixed(m.numVertices()), removed(m.numVertices());
  d.fixed.download(fixed.data(), fixed.size());
  d.removed.download(removed.data(), removed.size());
  int debris = 0;
  for (int v = 0; v < m.numVertices(); ++v) {
    const bool isDebris = m.mesh.vertices[v].x() < 0.005;
    debris += isDebris;
    EXPECT_EQ(removed[v], isDebris ? 1 : 0) << v;
    const bool anchored = v == 0 || v == m.numVertices() - 1;
    EXPECT_EQ(fixed[v], isDebris || anchored ? 1 : 0) << v;
    Vec3 expected = Vec3::Zero();
    if (anchored)
      expected = m.mesh.vertices[v] + Vec3(0, 0, 0.005);
    else if (isDebris)
      expected = s.x[v];
    for (int k = 0; k < 3; ++k) EXPECT_DOUBLE_EQ(x[3 * v + k], expected[k]) << v;
  }
  EXPECT_EQ(debris, 9);
  EXPECT_EQ(d.anchorCount, static_cast<size_t>(2 + debris - 1));
}

// A soft anchor holds nothing: its vertices stay free, each pulled by a spring of its weight
// toward its target; two springs on one vertex pull it toward their stiffness-weighted target.
TEST(HeldVertexSet, SoftAnchorsAreSpringsNotHeldVertices) {
  const SimModel m = buildSimModel(test::gridBar(2, 1, 1, 0.01), rubber());
  CpuExecutor ex;
  FrameData<CpuExecutor> d(m);
  HeldVertexSet<CpuExecutor> held(ex, m, d);
  AnchorConstraint a, b;
  a.vertices = {1, 2};
  a.origin = {Vec3(0.1, 0, 0), Vec3(0.2, 0, 0)};
  a.springWeights = {1.0, 0.25};
  b.vertices = {2};
  b.origin = {Vec3(0.4, 0, 0)};
  b.springWeights = {0.75};
  held.prepare({a, b}, 0.0);
  const int n = m.numVertices();
  std::vector<std::uint8_t> fixed(n);
  std::vector<double> k(n), target(3 * n);
  d.fixed.download(fixed.data(), n);
  d.springK.download(k.data(), n);
  d.springTarget.download(target.data(), 3 * n);
  for (int v = 0; v < n; ++v) EXPECT_EQ(fixed[v], 0) << "vertex " << v;
  const auto stiffness = [&](int v, double w) {
    return w * kAnchorSpring * m.material.lame.mu * std::cbrt(m.mass[v] / m.material.density);
  };
  EXPECT_DOUBLE_EQ(k[1], stiffness(1, 1.0));
  EXPECT_DOUBLE_EQ(k[2], stiffness(2, 0.25) + stiffness(2, 0.75));
  EXPECT_DOUBLE_EQ(target[3], 0.1);
  EXPECT_NEAR(target[6], 0.25 * 0.2 + 0.75 * 0.4, 1e-15);
  EXPECT_EQ(k[0], 0.0);
  EXPECT_EQ(d.anchorCount, 0u);
}

// Prepared again only when something moved: the same anchors (none on a path) and the same
// debris leave what the executor holds; another target, an anchor's path at a later time, new
// debris or debris held elsewhere are each taken.
TEST(HeldVertexSet, PreparesAgainOnlyWhenAnchorsPathsOrDebrisMoved) {
  DebrisBar bar;
  SimModel& m = bar.m;
  SimState& s = bar.s;
  FrameData<CpuExecutor>& d = bar.d;
  HeldVertexSet<CpuExecutor>& held = bar.held;
  const int n = m.numVertices(), last = n - 1;
  auto targetOf = [&](int v) {
    std::vector<double> x(3 * n, 0.0);
    d.x.upload(x);
    held.place();
    d.x.download(x.data(), x.size());
    return Vec3(x[3 * v], x[3 * v + 1], x[3 * v + 2]);
  };
  AnchorConstraint grip;
  grip.vertices = {last};
  grip.origin = {Vec3(1, 2, 3)};
  held.prepare({grip}, 0.0);
  EXPECT_EQ(targetOf(last), Vec3(1, 2, 3));
  held.prepare({grip}, 0.5);
  EXPECT_EQ(targetOf(last), Vec3(1, 2, 3)) << "nothing moved";
  grip.origin = {Vec3(4, 5, 6)};
  held.prepare({grip}, 0.5);
  EXPECT_EQ(targetOf(last), Vec3(4, 5, 6)) << "another target";
  AnchorConstraint moving;
  moving.vertices = {last};
  moving.path = {{0.0, Vec3::Zero()}, {1.0, Vec3(0, 0, 0.01)}};
  held.prepare({moving}, 0.5);
  EXPECT_NEAR(targetOf(last).z(), m.mesh.vertices[last].z() + 0.005, 1e-15);
  held.prepare({moving}, 1.0);
  EXPECT_NEAR(targetOf(last).z(), m.mesh.vertices[last].z() + 0.01, 1e-15) << "on its path";
  // Debris cut off, then held where the state has it, then moved there.
  cutAt(m, s, 0.005);
  held.updateRemovedDebris(censusPieces(m, s.damaged));
  held.holdRemovedAt(s);
  held.prepare({grip}, 1.0);
  EXPECT_EQ(targetOf(0), m.mesh.vertices[0]) << "the debris held where it is";
  held.prepare({grip}, 1.0);
  for (int v = 0; v < n; ++v)
    if (m.mesh.vertices[v].x() < 0.005) s.x[v] += Vec3(0, -0.003, 0);
  held.holdRemovedAt(s);
  held.prepare({grip}, 1.0);
  EXPECT_EQ(targetOf(0), s.x[0]) << "held where the state now has it";
  EXPECT_EQ(targetOf(last), Vec3(4, 5, 6));
}

}  // namespace
}  // namespace galsculpt

#include "solver/model/sim_model.h"

#include <gtest/gtest.h>

#include <numeric>
#include <stdexcept>

#include "tests/test_util.h"

namespace galsculpt {
namespace {

TEST(SimModel, MassEdgesAndScatterAreConsistentWithTheMesh) {
  const TetMesh mesh = test::gridBar(3, 2, 2, 0.1);
  MaterialParams material;
  material.density = 1200.0;
  const SimModel m = buildSimModel(mesh, material);
  EXPECT_EQ(m.numVertices(), mesh.numVertices());
  EXPECT_EQ(m.numTets(), mesh.numTets());
  EXPECT_EQ(m.edges, uniqueEdges(mesh));
  const double mass = std::accumulate(m.mass.begin(), m.mass.end(), 0.0);
  EXPECT_NEAR(mass, 1200.0 * totalVolume(mesh), 1e-12 * mass) << "lumped mass sums to rho V";
  for (int t = 0; t < m.numTets(); ++t) {
    for (int k = 0; k < 6; ++k) {
      const Edge& e = m.edges[m.tetEdges[t][k]];
      const int a = mesh.tets[t][kTetEdges[k][0]], b = mesh.tets[t][kTetEdges[k][1]];
      EXPECT_EQ(e, (Edge{std::min(a, b), std::max(a, b)}));
    }
  }
  // Colours: no two tets of one colour share a vertex, and every tet has one.
  std::vector<int> seen(m.numTets(), 0);
  for (const std::vector<int>& colour : m.colors) {
    std::vector<char> used(m.numVertices(), 0);
    for (int t : colour) {
      ++seen[t];
      for (int v : mesh.tets[t]) {
        EXPECT_FALSE(used[v]) << "tet " << t << " shares vertex " << v << " within a colour";
        used[v] = 1;
      }
    }
  }
  for (int t = 0; t < m.numTets(); ++t) EXPECT_EQ(seen[t], 1) << t;
}

// Every vertex's and every block's list holds exactly the element terms that add into it, each
// once, in colour order: each is then one thread's fixed-order sum, the same on every executor.
TEST(SimModel, AssemblyListsHoldEveryElementTermOnceInColourOrder) {
  const SimModel model = buildSimModel(test::gridBar(3, 2, 2, 0.1), MaterialParams{});
  std::vector<int> order(model.numTets());  // each tet's position in the colour order
  int next = 0;
  for (const std::vector<int>& colour : model.colors)
    for (int t : colour) order[t] = next++;
  std::vector<int> cornerSeen(4 * model.numTets(), 0);
  ASSERT_EQ(model.vertexSlotStart.size(), static_cast<size_t>(model.numVertices()) + 1);
  for (int v = 0; v < model.numVertices(); ++v) {
    for (int k = model.vertexSlotStart[v]; k < model.vertexSlotStart[v + 1]; ++k) {
      const int slot = model.vertexSlots[k];
      EXPECT_EQ(model.mesh.tets[slot / 4][slot % 4], v);
      ++cornerSeen[slot];
      if (k > model.vertexSlotStart[v]) {
        EXPECT_LT(order[model.vertexSlots[k - 1] / 4], order[slot / 4]);
      }
    }
  }
  for (int c : cornerSeen) EXPECT_EQ(c, 1);
  std::vector<int> blockSeen(16 * model.numTets(), 0);
  ASSERT_EQ(model.blockSlotStart.size(), static_cast<size_t>(model.numBlocks()) + 1);
  for (int b = 0; b < model.numBlocks(); ++b) {
    for (int k = model.blockSlotStart[b]; k < model.blockSlotStart[b + 1]; ++k) {
      const int slot = model.blockSlots[k];
      EXPECT_EQ(model.scatter[slot / 16][slot % 16], b);
      ++blockSeen[slot];
    }
  }
  for (int c : blockSeen) EXPECT_EQ(c, 1);
}

// The executors read the model's tets and tet edges as flat int arrays, in place.
TEST(SimModel, TetsAndTetEdgesReadAsFlatArrays) {
  const SimModel model = buildSimModel(test::gridBar(2, 2, 2, 0.1), MaterialParams{});
  const int* tets = model.tetVertexArray();
  const int* edges = model.tetEdgeArray();
  for (int t = 0; t < model.numTets(); ++t) {
    for (int a = 0; a < 4; ++a) EXPECT_EQ(tets[4 * t + a], model.mesh.tets[t][a]);
    for (int k = 0; k < 6; ++k) EXPECT_EQ(edges[6 * t + k], model.tetEdges[t][k]);
  }
}

TEST(SimModel, InitialStateIsAtRestAndUndamaged) {
  MaterialParams clay;
  clay.plastic.yieldStress = 5000.0;
  const SimModel m = buildSimModel(test::gridBar(2, 2, 2, 0.1), clay);
  const SimState s = initialState(m);
  EXPECT_EQ(s.x, m.mesh.vertices);
  for (const Vec3& v : s.v) EXPECT_TRUE(v.isZero(0.0));
  EXPECT_EQ(s.damaged, std::vector<std::uint8_t>(m.numEdges(), 0));
  EXPECT_EQ(s.crossing, std::vector<float>(m.numEdges(), kNoCrossing));
  ASSERT_EQ(s.plasticInverse.size(), static_cast<size_t>(m.numTets())) << "plastic material";
  EXPECT_TRUE(s.plasticInverse[0].isIdentity(0.0));
  EXPECT_EQ(countDamagePieces(m, s), 1);
  EXPECT_TRUE(s.anchors.empty()) << "nothing held until a scene or a tool says so";
  EXPECT_FALSE(m.fracture.enabled) << "no fracture field until one is built";
  const SimState elastic = initialState(buildSimModel(test::gridBar(2, 2, 2, 0.1), {}));
  EXPECT_TRUE(elastic.plasticInverse.empty());
}

TEST(SimModel, ADegenerateTetIsRefused) {
  TetMesh flat;
  flat.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0)};
  flat.tets = {{0, 1, 2, 3}};
  EXPECT_THROW(buildSimModel(flat, {}), std::invalid_argument);
}

}  // namespace
}  // namespace galsculpt

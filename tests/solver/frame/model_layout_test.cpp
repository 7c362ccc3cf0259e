#include "solver/frame/model_layout.h"

#include <gtest/gtest.h>

#include <map>

#include "tests/test_util.h"

namespace galsculpt {
namespace {

// Every output's contribution list holds exactly the element terms that add into it, each once,
// in the CPU's order (colour by colour): the device's gathers then sum what the CPU sums, in the
// same order.
TEST(DeviceLayout, ModelLayoutListsEveryContributionOnceInTheCpusOrder) {
  const SimModel model = buildSimModel(test::gridBar(3, 2, 2, 0.1), MaterialParams{});
  const ModelLayout m = buildModelLayout(model);
  ASSERT_EQ(m.vertices, model.numVertices());
  ASSERT_EQ(m.tets, model.numTets());
  ASSERT_EQ(m.tetVertices.size(), 4u * model.numTets());
  ASSERT_EQ(m.tetEdges.size(), 6u * model.numTets());
  for (int t = 0; t < model.numTets(); ++t)
    for (int k = 0; k < 6; ++k) EXPECT_EQ(m.tetEdges[6 * t + k], model.tetEdges[t][k]);
  // The position of each tet in the colour order.
  std::vector<int> order(model.numTets());
  int next = 0;
  for (const std::vector<int>& colour : model.colors)
    for (int t : colour) order[t] = next++;
  std::vector<int> cornerSeen(4 * model.numTets(), 0);
  for (int v = 0; v < m.vertices; ++v) {
    for (int k = m.vertexSlotStart[v]; k < m.vertexSlotStart[v + 1]; ++k) {
      const int slot = m.vertexSlots[k];
      EXPECT_EQ(model.mesh.tets[slot / 4][slot % 4], v);
      ++cornerSeen[slot];
      if (k > m.vertexSlotStart[v]) {
        EXPECT_LT(order[m.vertexSlots[k - 1] / 4], order[slot / 4]);
      }
    }
  }
  for (int c : cornerSeen) EXPECT_EQ(c, 1);
  std::vector<int> blockSeen(16 * model.numTets(), 0);
  for (int b = 0; b < m.blocks; ++b) {
    for (int k = m.blockSlotStart[b]; k < m.blockSlotStart[b + 1]; ++k) {
      const int slot = m.blockSlots[k];
      EXPECT_EQ(model.scatter[slot / 16][slot % 16], b);
      ++blockSeen[slot];
    }
  }
  for (int c : blockSeen) EXPECT_EQ(c, 1);
}

}  // namespace
}  // namespace galsculpt

// The plastic state (solver/frame/plastic_state.h) on the CPU executor: a clay bar stretched
// past yield flows where it is intact, not where it is damaged; what flowed goes back to the
// state; a saved state is restored exactly; syncIn says when the rest shapes changed.
#include <gtest/gtest.h>

#include "solver/frame/cpu_executor.h"
#include "solver/frame/plastic_state.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

struct ClayBar {
  SimModel m;
  SimState s;
  std::vector<double> x;
  ClayBar() {
    MaterialParams clay{MaterialModel::StVK, lameFromYoungPoisson(1e5, 0.3), 1000.0, {}};
    clay.plastic.yieldStress = 500.0;
    m = buildSimModel(test::gridBar(4, 1, 1, 0.01), clay);
    s = initialState(m);
    for (const Vec3& p : m.mesh.vertices) x.insert(x.end(), {1.05 * p.x(), p.y(), p.z()});
  }
};

TEST(PlasticState, FlowsPastYieldWhereIntactAndGivesItBack) {
  ClayBar bar;
  ASSERT_EQ(bar.s.plasticInverse.size(), static_cast<size_t>(bar.m.numTets()));
  CpuExecutor ex;
  PlasticState<CpuExecutor> plastic(ex, bar.m);
  EXPECT_TRUE(plastic.syncIn(bar.s, bar.m.rest.data())) << "the first state: shapes computed";
  EXPECT_FALSE(plastic.syncIn(bar.s, bar.m.rest.data())) << "the same state again";
  EXPECT_TRUE(plastic.active());
  std::vector<std::uint8_t> damaged(bar.m.numEdges(), 0);
  damaged[bar.m.tetEdges[0][0]] = 1;  // element 0 (and its neighbours on that edge) cracked
  std::vector<double> flowed(bar.m.numTets());
  plastic.save();
  const int count = plastic.returnMap(bar.x.data(), damaged.data(), bar.m.tetVertexArray(),
                                      bar.m.tetEdgeArray(), bar.m.rest.data(), flowed.data());
  EXPECT_GT(count, 0);
  EXPECT_LT(count, bar.m.numTets()) << "the cracked elements do not flow";
  EXPECT_EQ(flowed[0], 0.0);
  EXPECT_TRUE(plastic.flowed());
  ASSERT_NE(plastic.shaped(), nullptr);
  int shaped = 0;
  for (int t = 0; t < bar.m.numTets(); ++t) shaped += plastic.shaped()[t];
  EXPECT_EQ(shaped, count) << "a plastic rest shape for every element that flowed";
  SimState out = bar.s;
  plastic.syncOut(out);
  int changed = 0;
  for (int t = 0; t < bar.m.numTets(); ++t)
    changed += out.plasticInverse[t] != bar.s.plasticInverse[t];
  EXPECT_EQ(changed, count);
  for (int t = 0; t < bar.m.numTets(); ++t)
    EXPECT_EQ(out.plasticStrain[t] > 0.0, flowed[t] > 0.0) << t;
  // Rolled back: the saved state exactly, and no rest shape left.
  plastic.restore(bar.m.rest.data());
  SimState back = bar.s;
  back.plasticInverse.assign(back.plasticInverse.size(), Eigen::Matrix3d::Zero());
  plastic.syncOut(back);
  EXPECT_EQ(back.plasticInverse, bar.s.plasticInverse);
  for (int t = 0; t < bar.m.numTets(); ++t) EXPECT_EQ(plastic.shaped()[t], 0);
  // A state that flowed elsewhere: its rest shapes change on the way in.
  EXPECT_TRUE(plastic.syncIn(out, bar.m.rest.data()));
  EXPECT_FALSE(plastic.syncIn(out, bar.m.rest.data())) << "nothing new";
}

TEST(PlasticState, AnElasticStateIsNotActive) {
  ClayBar bar;
  bar.s.plasticInverse.clear();
  bar.s.plasticStrain.clear();
  CpuExecutor ex;
  PlasticState<CpuExecutor> plastic(ex, bar.m);
  EXPECT_FALSE(plastic.syncIn(bar.s, bar.m.rest.data()));
  EXPECT_FALSE(plastic.active());
  EXPECT_EQ(plastic.shapes(), nullptr);
  EXPECT_EQ(plastic.shaped(), nullptr);
}

}  // namespace
}  // namespace galsculpt

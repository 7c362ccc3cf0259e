#include "solver/multigrid/multigrid_layout.h"

#include <gtest/gtest.h>

#include "solver/model/sim_model.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

// Each coarse block's contribution list holds exactly the finer blocks that the hierarchy maps
// into it, each once, with the finer row each lies in: the refresh then sums every term of
// U^T A U once, on every executor.
TEST(MultigridLayout, RefreshListsHoldEveryFinerBlockOnceWithItsRow) {
  const SimModel model = buildSimModel(test::gridBar(3, 8, 3, 0.05), MaterialParams{});
  const Multigrid mg(model.pattern, model.mesh.vertices, model.edges, {24, 6});
  const MultigridLayout layout = buildMultigridLayout(mg, model.pattern);
  ASSERT_EQ(layout.levels.size(), 2u);
  for (int l = 0; l < 2; ++l) {
    const MultigridLevel& level = mg.level(l);
    const LevelLayout& ll = layout.levels[l];
    const std::vector<int>& finerStart = l == 0 ? model.pattern.rowStart : mg.level(0).rowStart;
    const std::vector<int>& map = l == 0 ? level.fineToCoarseBlock : level.finerToCoarseBlock;
    std::vector<int> seen(map.size(), 0);
    ASSERT_EQ(ll.contribStart.size(), level.columns.size() + 1);
    for (size_t c = 0; c + 1 < ll.contribStart.size(); ++c) {
      for (int i = ll.contribStart[c]; i < ll.contribStart[c + 1]; ++i) {
        const int k = ll.contribBlock[i], row = ll.contribRow[i];
        EXPECT_EQ(map[k], static_cast<int>(c));
        EXPECT_GE(k, finerStart[row]);
        EXPECT_LT(k, finerStart[row + 1]) << "block " << k << " lies in row " << row;
        ++seen[k];
      }
    }
    for (size_t k = 0; k < map.size(); ++k) EXPECT_EQ(seen[k], map[k] >= 0 ? 1 : 0) << k;
    for (int h = 0; h < ll.handles; ++h) {
      ASSERT_GE(ll.diagonal[h], 0);
      EXPECT_EQ(ll.columns[ll.diagonal[h]], h);
      EXPECT_EQ(ll.memberStart[h + 1] - ll.memberStart[h],
                static_cast<int>(level.members[h].size()));
      EXPECT_EQ(ll.empty[h], level.members[h].empty() ? 1 : 0);
    }
  }
}

}  // namespace
}  // namespace galsculpt

#include "solver/mesh/csr.h"

#include <gtest/gtest.h>

namespace galsculpt {
namespace {

TEST(Csr, FlattenGroupsKeepsOrderAndEmptyGroups) {
  std::vector<int> start = {7}, items = {9, 9};  // overwritten, not appended to
  flattenGroups({{3, 1}, {}, {2}, {}}, start, items);
  EXPECT_EQ(start, (std::vector<int>{0, 2, 2, 3, 3}));
  EXPECT_EQ(items, (std::vector<int>{3, 1, 2}));
  flattenGroups({}, start, items);
  EXPECT_EQ(start, std::vector<int>{0});
  EXPECT_TRUE(items.empty());
}

}  // namespace
}  // namespace galsculpt

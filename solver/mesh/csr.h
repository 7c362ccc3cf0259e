// Compressed rows (CSR) from per-row lists: the flat form the executors read.
#pragma once

#include <vector>

namespace galsculpt {

// start[i] .. start[i + 1] index the items of group i (start has groups + 1 entries).
inline void flattenGroups(const std::vector<std::vector<int>>& groups, std::vector<int>& start,
                          std::vector<int>& items) {
  start.assign(1, 0);
  items.clear();
  for (const std::vector<int>& g : groups) {
    items.insert(items.end(), g.begin(), g.end());
    start.push_back(static_cast<int>(items.size()));
  }
}

}  // namespace galsculpt

#include "solver/mesh/union_find.h"

#include <gtest/gtest.h>

#include <random>

namespace galsculpt {
namespace {

TEST(UnionFind, UnitesAndCountsLikeABruteForceLabelling) {
  const int n = 200;
  UnionFind uf(n);
  std::vector<int> label(n);
  for (int i = 0; i < n; ++i) label[i] = i;
  std::mt19937 rng(8);
  std::uniform_int_distribution<int> pick(0, n - 1);
  int sets = n;
  for (int k = 0; k < 150; ++k) {
    const int a = pick(rng), b = pick(rng);
    const bool merged = label[a] != label[b];
    EXPECT_EQ(uf.unite(a, b), merged);
    if (merged) {
      const int from = label[b], to = label[a];
      for (int& l : label)
        if (l == from) l = to;
      --sets;
    }
  }
  int roots = 0;
  for (int i = 0; i < n; ++i) {
    roots += uf.find(i) == i;
    for (int j = 0; j < n; j += 7) EXPECT_EQ(uf.find(i) == uf.find(j), label[i] == label[j]);
  }
  EXPECT_EQ(roots, sets);
}

}  // namespace
}  // namespace galsculpt

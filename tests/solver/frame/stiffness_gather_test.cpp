// The host's stiffness gather by row ranges (solver/frame/stiffness_gather.h) against the sum a
// thread per block makes (ElasticTerm::gatherUpperByBlocks, a device's): the same bits
// in every block, with zero stiffnesses skipped, with only fresh elements' blocks or only touched
// rows' blocks summed again, at any thread count.
#include "solver/frame/stiffness_gather.h"

#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <utility>
#include <vector>

#include "solver/frame/parallel.h"
#include "solver/model/sim_model.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

// A grid bar whose tets list their corners in shuffled (even) orders, so that an element's
// upper blocks land both above and below the diagonal of the assembled matrix.
SimModel shuffledBar() {
  TetMesh mesh = test::gridBar(6, 5, 4, 0.01);
  std::mt19937 gen(11);
  for (Tet& t : mesh.tets) {
    const int turns = static_cast<int>(gen() % 3);
    for (int i = 0; i < turns; ++i) t = Tet{t[1], t[2], t[0], t[3]};
    if (gen() % 2) t = Tet{t[1], t[0], t[3], t[2]};
  }
  MaterialParams material{
      MaterialModel::StableNeoHookean, lameFromYoungPoisson(1e5, 0.4), 1000.0, {}};
  return buildSimModel(mesh, material);
}

// What a thread per block sums into block b (on and above the diagonal), or false where it
// leaves the block as it was.
bool sumOfBlock(const SimModel& m, int row, int b, const std::vector<double>& packed,
                const std::vector<std::uint8_t>& opened, const std::uint8_t* fresh,
                const std::uint8_t* touched, double out[9]) {
  const int col = m.pattern.columns[b];
  if (touched && !(touched[row] && touched[col])) return false;
  if (fresh) {
    bool any = false;
    for (int i = m.blockSlotStart[b]; i < m.blockSlotStart[b + 1]; ++i)
      any = any || fresh[m.blockSlots[i] / 16];
    if (!any) return false;
  }
  for (int e = 0; e < 9; ++e) out[e] = 0.0;
  for (int i = m.blockSlotStart[b]; i < m.blockSlotStart[b + 1]; ++i) {
    const int slot = m.blockSlots[i], t = slot / 16, a = (slot % 16) / 4, c = slot % 4;
    if (ElementPass::zeroStiffness(opened[t])) continue;
    const double* h = packed.data() + ElementPass::kPackedHessian * static_cast<size_t>(t);
    if (a <= c) {
      const double* blk = h + 9 * ElementPass::packedBlock(a, c);
      for (int e = 0; e < 9; ++e) out[e] += blk[e];
    } else {
      const double* blk = h + 9 * ElementPass::packedBlock(c, a);
      for (int j = 0; j < 3; ++j)
        for (int r = 0; r < 3; ++r) out[r + 3 * j] += blk[j + 3 * r];
    }
  }
  return true;
}

TEST(StiffnessGather, SumsEveryBlockAsAThreadPerBlockDoes) {
  const SimModel m = shuffledBar();
  const int tets = m.numTets(), blocks = m.numBlocks(), n = m.numVertices();
  for (int b = 0; b < blocks; ++b)
    for (int i = m.blockSlotStart[b] + 1; i < m.blockSlotStart[b + 1]; ++i)
      ASSERT_LT(m.blockSlots[i - 1] / 16, m.blockSlots[i] / 16)
          << "a block's terms in element order";
  std::mt19937 gen(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> packed(ElementPass::kPackedHessian * static_cast<size_t>(tets));
  for (double& v : packed) v = u(gen);
  std::vector<std::uint8_t> opened(tets, 0), fresh(tets), touched(n);
  for (int t = 0; t < tets; t += 9) opened[t] = kernels::kIntact;
  ASSERT_TRUE(ElementPass::zeroStiffness(opened[0]));
  for (std::uint8_t& f : fresh) f = gen() % 10 < 3;
  for (std::uint8_t& f : touched) f = gen() % 10 < 6;
  std::vector<double> before(9 * static_cast<size_t>(blocks));
  for (double& v : before) v = u(gen);
  const std::vector<std::pair<const std::uint8_t*, const std::uint8_t*>> cases = {
      {nullptr, nullptr},
      {fresh.data(), nullptr},
      {nullptr, touched.data()},
      {fresh.data(), touched.data()}};
  StiffnessGather gather(m.pattern, m.scatter, m.tetVertexArray());
  for (const auto& [f, tv] : cases) {
    std::vector<double> expected = before;
    int summed = 0, kept = 0;
    for (int r = 0; r < n; ++r)
      for (int b = m.pattern.rowStart[r]; b < m.pattern.rowStart[r + 1]; ++b) {
        if (m.pattern.columns[b] < r) continue;
        const bool sums = sumOfBlock(m, r, b, packed, opened, f, tv, expected.data() + 9 * b);
        (sums ? summed : kept) += 1;
      }
    EXPECT_GT(summed, 100);
    if (f || tv) {
      EXPECT_GT(kept, 10);
    }
    for (const int threads : {1, 2, 3}) {
      setThreadCount(threads);
      std::vector<double> kb = before;
      gather.gatherUpper(packed.data(), opened.data(), f, tv, kb.data());
      EXPECT_EQ(std::memcmp(kb.data(), expected.data(), kb.size() * sizeof(double)), 0)
          << threads << " threads, fresh " << (f != nullptr) << ", touched " << (tv != nullptr);
    }
  }
  setThreadCount(0);
}

}  // namespace
}  // namespace galsculpt

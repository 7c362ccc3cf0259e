// The pass terms' list (solver/frame/pass_terms.h) with three toy terms whose values make every
// order of a sum give other bits (1e16, -1e16 and 1: only ((1e16 - 1e16) + 1) is 1): the
// gradient written by the first term and added to by the others in list order, the energies
// folded left, the vertex shares from the last term to the first, the diagonal blocks in list
// order, each stage called on every term in list order; and the frame's own list.
#include "solver/frame/pass_terms.h"

#include <gtest/gtest.h>

#include <string>
#include <type_traits>
#include <vector>

#include "solver/frame/cpu_executor.h"
#include "solver/frame/incremental_potential.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

constexpr double kValue[3] = {1e16, -1e16, 1.0};
std::vector<std::string> calls;  // the toy terms' calls, in order

template <typename Exec, int K>
struct Toy {
  explicit Toy(const PassTermContext<Exec>&) {}
  double energy[2] = {kValue[K], kValue[K]};  // at x, at the trial
  double* energySlot(FrameScalars*, bool trial) { return &energy[trial ? 1 : 0]; }
  void atIterate(FrameData<Exec>& d, const double*, bool, double* gradient) {
    calls.push_back("iterate " + std::to_string(K));
    for (int i = 0; i < 3 * d.n; ++i) gradient[i] = K == 0 ? kValue[K] : gradient[i] + kValue[K];
  }
  void atTrial(FrameData<Exec>& d, const double*, const std::uint8_t*, double* gradient) {
    calls.push_back("trial " + std::to_string(K));
    if (gradient)
      for (int i = 0; i < 3 * d.n; ++i) gradient[i] = K == 0 ? kValue[K] : gradient[i] + kValue[K];
  }
  void atAccepted(FrameData<Exec>&, const double*, double*) {
    calls.push_back("accepted " + std::to_string(K));
  }
  struct VertexShare {
    GALSCULPT_HD void add(int, double& sum) const { sum += kValue[K]; }
  };
  VertexShare vertexShare(FrameData<Exec>&, bool) const { return {}; }
  struct Blocks {
    GALSCULPT_HD void add(int, const double*, double* out) const { out[0] += kValue[K]; }
  };
  Blocks diagonalBlocks(FrameData<Exec>&) const { return {}; }
};
template <typename Exec>
using Big = Toy<Exec, 0>;
template <typename Exec>
using MinusBig = Toy<Exec, 1>;
template <typename Exec>
using One = Toy<Exec, 2>;

struct Fixture {
  SimModel model =
      buildSimModel(test::gridBar(1, 1, 1, 0.01),
                    {MaterialModel::StableNeoHookean, lameFromYoungPoisson(1e5, 0.4), 1000.0, {}});
  CpuExecutor ex;
  FrameData<CpuExecutor> d{model};
  PlasticState<CpuExecutor> plastic{ex, model};
  PassTermList<CpuExecutor, Big, MinusBig, One> terms{{ex, model, d, plastic}};
};

TEST(PassTerms, EachStageCallsTheTermsInListOrder) {
  Fixture f;
  calls.clear();
  std::vector<double> y(3 * f.d.n, 0.0), gradient(3 * f.d.n, 7.0);
  f.terms.atIterate(y.data(), false, gradient.data());
  f.terms.atTrial(y.data(), nullptr);
  f.terms.atAccepted(y.data(), gradient.data());
  const std::vector<std::string> expected = {"iterate 0",  "iterate 1",  "iterate 2",
                                             "trial 0",    "trial 1",    "trial 2",
                                             "accepted 0", "accepted 1", "accepted 2"};
  EXPECT_EQ(calls, expected);
}

TEST(PassTerms, TheFirstWritesTheGradientAndTheOthersAddInOrder) {
  Fixture f;
  std::vector<double> y(3 * f.d.n, 0.0), gradient(3 * f.d.n, 7.0);
  f.terms.atIterate(y.data(), false, gradient.data());
  for (double g : gradient) EXPECT_EQ(g, 1.0) << "((1e16 - 1e16) + 1), and the 7 overwritten";
  std::vector<double> atTrial(3 * f.d.n, 7.0);
  f.terms.atTrial(y.data(), nullptr, atTrial.data());
  for (double g : atTrial) EXPECT_EQ(g, 1.0) << "a trial's gradient in the same order";
}

TEST(PassTerms, EnergiesFoldLeftSharesFromTheLastAndBlocksInOrder) {
  Fixture f;
  EXPECT_EQ(f.terms.energies(false).sum(), 1.0) << "((1e16 - 1e16) + 1)";
  EXPECT_EQ(f.terms.energies(true).sum(), 1.0);
  double share = 0.0;
  f.terms.vertexShares(false).add(0, share);
  EXPECT_EQ(share, 0.0) << "((1 - 1e16) + 1e16): the last term's share first";
  double block[9] = {};
  const double y[3] = {};
  f.terms.diagonalBlocks().add(0, y, block);
  EXPECT_EQ(block[0], 1.0) << "((1e16 - 1e16) + 1)";
}

TEST(PassTerms, TheFramesListIsTheElementsThenTheColliders) {
  // Their order is in the frame's pinned bits (determinism_test.cpp).
  static_assert(
      std::is_same_v<PassTerms<CpuExecutor>, PassTermList<CpuExecutor, ElasticTerm, ContactTerm>>);
  Fixture f;
  IncrementalPotential<CpuExecutor> potential(f.ex, f.model, f.d, f.plastic);
  EXPECT_EQ(&potential.passTerms().term<ElasticTerm<CpuExecutor>>(), &potential.elastic());
  EXPECT_EQ(&potential.passTerms().term<ContactTerm<CpuExecutor>>(), &potential.contact());
}

}  // namespace
}  // namespace galsculpt

// The fracture pass (solver/frame/fracture_pass.h) on the CPU executor, on a bar stretched
// uniformly along x: which edges break under the stress and the strain criteria, that the count
// and the largest criticality it reports are those of its per-edge ratios, that only the most
// critical break under criticalFraction, and that markBroken damages exactly those.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "solver/fracture/fracture.h"
#include "solver/frame/cpu_executor.h"
#include "solver/frame/fracture_pass.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

struct StretchedBar {
  SimModel m;
  std::vector<double> x;
  std::vector<std::uint8_t> damaged;
  StretchedBar(double stretch, const FractureSettings& settings) {
    m = buildSimModel(
        test::gridBar(6, 1, 1, 0.01),
        {MaterialModel::StableNeoHookean, lameFromYoungPoisson(1e6, 0.3), 1000.0, {}});
    m.fracture = buildFractureField(m, settings);
    for (const Vec3& p : m.mesh.vertices) x.insert(x.end(), {(1 + stretch) * p.x(), p.y(), p.z()});
    damaged.assign(m.numEdges(), 0);
  }
  ElementInputs inputs() const {
    return {m.tetVertexArray(),
            m.tetEdgeArray(),
            damaged.data(),
            m.rest.data(),
            nullptr,
            nullptr,
            nullptr};
  }
  double strain(int e) const {
    const int a = m.edges[e][0], b = m.edges[e][1];
    const Vec3 d(x[3 * b] - x[3 * a], x[3 * b + 1] - x[3 * a + 1], x[3 * b + 2] - x[3 * a + 2]);
    return d.norm() / (m.mesh.vertices[b] - m.mesh.vertices[a]).norm() - 1.0;
  }
};

FractureSettings stress(double threshold) {
  FractureSettings s;
  s.threshold = threshold;
  return s;
}

TEST(FracturePass, EdgesPastTheirThresholdBreakAndOnlyThose) {
  // 1 % stretch (no lateral contraction) of E = 1 MPa, nu = 0.3: about 13.5 kPa along x, 5.8 kPa
  // across, 9.6 kPa along the face diagonals.
  for (const double threshold : {8e3, 2e4}) {
    StretchedBar bar(0.01, stress(threshold));
    CpuExecutor ex;
    FracturePass<CpuExecutor> pass(ex, bar.m);
    const FractureReport report = pass.findBreaks(bar.inputs(), bar.x.data(), bar.damaged.data());
    const double* ratio = pass.stressRatio();
    int over = 0;
    double largest = 0.0;
    for (int e = 0; e < bar.m.numEdges(); ++e) {
      over += ratio[e] > 1.0;
      largest = std::max(largest, ratio[e]);
    }
    EXPECT_EQ(report.newlyDamaged, over) << threshold;
    EXPECT_DOUBLE_EQ(report.maxStressRatio, largest);
    EXPECT_EQ(over > 0, threshold < 1e4) << "largest ratio " << largest;
    pass.markBroken(bar.damaged.data());
    for (int e = 0; e < bar.m.numEdges(); ++e) {
      EXPECT_EQ(bar.damaged[e], ratio[e] > 1.0 ? 1 : 0);
      if (bar.damaged[e]) {
        EXPECT_GT(bar.strain(e), 0.001) << "a stretched edge";
      }
    }
  }
}

TEST(FracturePass, TheStrainCriterionBreaksTheEdgesStretchedPastItsLimit) {
  FractureSettings s;
  s.strainThreshold = 0.005;  // the x edges stretch 1 %, the diagonals less, the others not
  StretchedBar bar(0.01, s);
  CpuExecutor ex;
  FracturePass<CpuExecutor> pass(ex, bar.m);
  const FractureReport report = pass.findBreaks(bar.inputs(), bar.x.data(), bar.damaged.data());
  pass.markBroken(bar.damaged.data());
  int expected = 0;
  for (int e = 0; e < bar.m.numEdges(); ++e) {
    expected += bar.strain(e) > 0.005;
    EXPECT_EQ(bar.damaged[e], bar.strain(e) > 0.005 ? 1 : 0) << e;
  }
  EXPECT_GT(expected, 0);
  EXPECT_EQ(report.newlyDamaged, expected);
  EXPECT_NEAR(report.maxStressRatio, 0.01 / 0.005, 1e-9) << "strain over its limit";
}

TEST(FracturePass, TheMostCriticalBreakFirst) {
  FractureSettings s = stress(8e3);
  StretchedBar all(0.01, s);
  s.criticalFraction = 0.999;
  StretchedBar first(0.01, s);
  CpuExecutor ex;
  FracturePass<CpuExecutor> a(ex, all.m), b(ex, first.m);
  const int everything = a.findBreaks(all.inputs(), all.x.data(), all.damaged.data()).newlyDamaged;
  const FractureReport critical =
      b.findBreaks(first.inputs(), first.x.data(), first.damaged.data());
  EXPECT_GT(critical.newlyDamaged, 0);
  EXPECT_LT(critical.newlyDamaged, everything);
  b.markBroken(first.damaged.data());
  for (int e = 0; e < first.m.numEdges(); ++e)
    if (first.damaged[e]) {
      EXPECT_GE(b.stressRatio()[e], 0.999 * critical.maxStressRatio);
    }
}

}  // namespace
}  // namespace galsculpt

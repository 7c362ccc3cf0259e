// Where a local Newton iteration solves (solver/frame/local_region.h): the region holds the
// residual, what is left outside is within its share of the target, it reaches kRings rings past
// the vertices it was chosen by and never takes a held vertex; a residual spread over the body,
// or one that is not finite, is solved whole.
#include "solver/frame/local_region.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "solver/frame/cpu_executor.h"
#include "solver/frame/device_like_executor.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

template <typename Exec>
struct BodyOn {
  SimModel model =
      buildSimModel(test::gridBar(16, 4, 4, 0.01),
                    {MaterialModel::StableNeoHookean, lameFromYoungPoisson(1e5, 0.4), 1000.0, {}});
  Exec ex;
  FrameData<Exec> d{model};
  LocalRegion<Exec> region{ex, d};
  int n = model.numVertices();
  std::vector<std::uint8_t> fixed = std::vector<std::uint8_t>(n, 0);

  BodyOn() {
    for (int v = 0; v < n; ++v) fixed[v] = model.mesh.vertices[v].x() == 0.0;  // one end held
    d.fixed.upload(fixed);
  }
  template <typename T>
  std::vector<T> read(const typename Exec::template Buffer<T>& b, size_t size) const {
    std::vector<T> out(size);
    b.download(out.data(), size);
    return out;
  }
  // g: `hot` on the vertices in x in (0.075, 0.085), `cold` on the other free ones.
  void residual(double hot, double cold) {
    std::vector<double> g(3 * n, 0.0);
    for (int v = 0; v < n; ++v) {
      if (fixed[v]) continue;
      const double x = model.mesh.vertices[v].x();
      const double value = x > 0.075 && x < 0.085 ? hot : cold;
      for (int k = 0; k < 3; ++k) g[3 * v + k] = value * (k + 1);
    }
    d.g.upload(g);
  }
};
using Body = BodyOn<CpuExecutor>;

TEST(LocalRegion, HoldsTheResidualAndReachesTwoRingsPastIt) {
  Body b;
  b.residual(1.0, 1e-4);
  const double target = 0.5;  // |g| outside the hot layer: 1e-4 sqrt(14 n), about 0.01
  ASSERT_TRUE(b.region.choose(target));
  const std::vector<std::uint8_t> region = b.read(b.d.regionVertex, b.n);
  const std::vector<std::uint8_t> regionFixed = b.read(b.d.regionFixed, b.n);
  const std::vector<std::uint8_t> element = b.read(b.d.regionElement, b.model.numTets());
  std::vector<double> g(3 * b.n);
  b.d.g.download(g.data(), g.size());
  double outside = 0.0;
  int count = 0;
  for (int v = 0; v < b.n; ++v) {
    const double x = b.model.mesh.vertices[v].x();
    count += region[v];
    EXPECT_EQ(regionFixed[v], b.fixed[v] || !region[v]) << "vertex " << v;
    if (!region[v])
      for (int k = 0; k < 3; ++k) outside += g[3 * v + k] * g[3 * v + k];
    // The hot layer is x = 0.08; its neighbours reach one grid step, two rings two steps.
    if (x > 0.055 && x < 0.105) {
      EXPECT_TRUE(region[v]) << "vertex " << v << " at x " << x;
    }
    if (x < 0.045 || x > 0.115) {
      EXPECT_FALSE(region[v]) << "vertex " << v << " at x " << x;
    }
  }
  EXPECT_EQ(b.region.vertices(), count);
  EXPECT_LE(outside, 0.25 * target * target);
  for (int t = 0; t < b.model.numTets(); ++t) {
    bool touches = false;
    for (int a = 0; a < 4; ++a) touches = touches || region[b.model.mesh.tets[t][a]];
    ASSERT_EQ(element[t], touches ? 1 : 0) << "element " << t;
  }
}

TEST(LocalRegion, NeverTakesAHeldVertex) {
  Body b;
  b.residual(0.0, 0.0);
  std::vector<double> g(3 * b.n, 0.0);
  for (int v = 0; v < b.n; ++v)  // the free vertices next to the held end
    if (!b.fixed[v] && b.model.mesh.vertices[v].x() < 0.015) g[3 * v] = 1.0;
  b.d.g.upload(g);
  ASSERT_TRUE(b.region.choose(0.1));
  const std::vector<std::uint8_t> region = b.read(b.d.regionVertex, b.n);
  for (int v = 0; v < b.n; ++v)
    if (b.fixed[v]) {
      EXPECT_FALSE(region[v]) << "vertex " << v;
    }
}

TEST(LocalRegion, AResidualSpreadOverTheBodyIsSolvedWhole) {
  Body b;
  b.residual(1.0, 1.0);
  EXPECT_FALSE(b.region.choose(1.0));
}

TEST(LocalRegion, AResidualThatIsNotFiniteIsSolvedWhole) {
  Body b;
  b.residual(1.0, 1e-6);
  std::vector<double> g(3 * b.n);
  b.d.g.download(g.data(), g.size());
  g[3 * (b.n - 1)] = std::numeric_limits<double>::quiet_NaN();
  b.d.g.upload(g);
  EXPECT_FALSE(b.region.choose(1.0));
  g[3 * (b.n - 1)] = std::numeric_limits<double>::infinity();
  b.d.g.upload(g);
  EXPECT_FALSE(b.region.choose(1.0));
}

// A device finds the seeds' threshold where the residuals are (LocalRegion::seedOnDevice): the
// host's region, to the vertex, with one wait where the host downloads every |g_v|^2 and reads.
TEST(LocalRegion, ADeviceChoosesTheHostsRegionWithOneWait) {
  struct Case {
    double hot, cold, target;
    bool notFinite;
  };
  int regions = 0;
  for (const Case c : {Case{1.0, 1e-4, 0.5, false}, Case{2.0, 1e-5, 0.05, false},
                       Case{1.0, 1.0, 1.0, false}, Case{1.0, 1e-6, 1.0, true}}) {
    Body host;
    BodyOn<DeviceLikeExecutor> device;
    host.residual(c.hot, c.cold);
    device.residual(c.hot, c.cold);
    if (c.notFinite) {
      std::vector<double> g(3 * host.n);
      host.d.g.download(g.data(), g.size());
      g[3 * (host.n - 1)] = std::numeric_limits<double>::quiet_NaN();
      host.d.g.upload(g);
      device.d.g.upload(g);
    }
    const long waits = device.ex.counters().waits;
    const bool onHost = host.region.choose(c.target), onDevice = device.region.choose(c.target);
    EXPECT_EQ(onDevice, onHost) << c.cold << " " << c.target;
    EXPECT_EQ(device.ex.counters().waits - waits, 1) << "the region's size, nothing else";
    if (!onHost) continue;
    ++regions;
    EXPECT_EQ(device.read(device.d.regionVertex, device.n), host.read(host.d.regionVertex, host.n));
    EXPECT_EQ(device.region.vertices(), host.region.vertices());
  }
  EXPECT_EQ(regions, 2) << "two of the cases have a region, two are solved whole";
}

}  // namespace
}  // namespace galsculpt

// The contact term (solver/frame/contact_term.h) on the CPU executor: its gradient against
// finite differences of its energy, its stiffness blocks against finite differences of its
// gradient (a plane: the penalty is then exactly quadratic), the forces it reads back against
// its gradient, anchored vertices and a model without colliders.
#include <gtest/gtest.h>

#include <cmath>

#include "solver/frame/contact_term.h"
#include "solver/frame/cpu_executor.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

SimModel barOverColliders(Collider::Type type) {
  SimModel m =
      buildSimModel(test::gridBar(4, 1, 1, 0.01),
                    {MaterialModel::StableNeoHookean, lameFromYoungPoisson(1e5, 0.4), 1000.0, {}});
  Collider c;
  c.type = type;
  if (type == Collider::Type::Plane) {
    c.point = Vec3(0, 0.0043, 0);  // the bar's lower vertices inside, none on the surface
    c.normal = Vec3(0.2, 1, 0).normalized();
  } else {
    c.center = Vec3(0.02, -0.05, 0.005);
    c.radius = 0.052;  // the middle of the bar's bottom inside
  }
  m.colliders.push_back(c);
  return m;
}

struct Energy {
  CpuExecutor ex;
  ContactTerm<CpuExecutor> term;
  std::vector<std::uint8_t> fixed;
  double h = 0.01;
  explicit Energy(const SimModel& m) : term(ex, m), fixed(m.numVertices(), 0) {
    term.place({ColliderState{}}, 0.0, h);
  }
  double operator()(const SimModel& m, const std::vector<double>& y, std::vector<double>* g) {
    double e = 0.0;
    if (g) g->assign(y.size(), 0.0);
    term.energy(y.data(), fixed.data(), m.mass.data(), h, g ? g->data() : nullptr, &e);
    return e;
  }
};

std::vector<double> positions(const SimModel& m) {
  std::vector<double> y;
  for (const Vec3& p : m.mesh.vertices) y.insert(y.end(), {p.x(), p.y(), p.z()});
  return y;
}

TEST(ContactTerm, GradientIsTheEnergysDerivative) {
  for (const auto type : {Collider::Type::Plane, Collider::Type::Sphere}) {
    const SimModel m = barOverColliders(type);
    Energy energy(m);
    std::vector<double> y = positions(m), g;
    const double e = energy(m, y, &g);
    ASSERT_GT(e, 0.0) << "some vertices inside";
    double worst = 0.0, scale = 0.0;
    for (size_t i = 0; i < y.size(); ++i) {
      const double step = 1e-7, keep = y[i];
      y[i] = keep + step;
      const double up = energy(m, y, nullptr);
      y[i] = keep - step;
      const double down = energy(m, y, nullptr);
      y[i] = keep;
      worst = std::max(worst, std::abs((up - down) / (2 * step) - g[i]));
      scale = std::max(scale, std::abs(g[i]));
    }
    EXPECT_LT(worst, 1e-6 * scale) << static_cast<int>(type);
  }
}

TEST(ContactTerm, StiffnessIsTheGradientsDerivativeOnAPlane) {
  const SimModel m = barOverColliders(Collider::Type::Plane);
  Energy energy(m);
  std::vector<double> y = positions(m), g0, g1;
  energy(m, y, &g0);
  const auto stiffness = energy.term.stiffness(m.mass.data(), energy.h);
  int inside = 0;
  for (int v = 0; v < m.numVertices(); ++v) {
    double block[9] = {};
    stiffness.add(v, y.data(), block);
    if (block[0] == 0.0) continue;
    ++inside;
    for (int j = 0; j < 3; ++j) {
      const double step = 1e-7;
      y[3 * v + j] += step;
      energy(m, y, &g1);
      y[3 * v + j] -= step;
      for (int i = 0; i < 3; ++i)
        EXPECT_NEAR((g1[3 * v + i] - g0[3 * v + i]) / step, block[i + 3 * j],
                    1e-6 * std::abs(block[0]));
    }
  }
  EXPECT_GT(inside, 0);
}

TEST(ContactTerm, ReadsBackTheForceTheBodyTakes) {
  const SimModel m = barOverColliders(Collider::Type::Sphere);
  Energy energy(m);
  const std::vector<double> y = positions(m);
  std::vector<double> g;
  energy(m, y, &g);
  energy.term.sumForces(y.data(), energy.fixed.data(), m.mass.data(), energy.h);
  std::vector<Vec3> forces;
  std::vector<double> moments;
  energy.term.readForces(forces, moments);
  ASSERT_EQ(forces.size(), 1u);
  Vec3 minusGradient = Vec3::Zero();
  for (int v = 0; v < m.numVertices(); ++v)
    minusGradient -= Vec3(g[3 * v], g[3 * v + 1], g[3 * v + 2]);
  EXPECT_GT(forces[0].y(), 0.0) << "pushed up, out of the sphere";
  EXPECT_LT((forces[0] - minusGradient).norm(), 1e-9 * minusGradient.norm());
  EXPECT_EQ(moments[0], 0.0) << "not a pendulum";
}

TEST(ContactTerm, AnchoredVerticesAndNoCollidersTakeNone) {
  SimModel m = barOverColliders(Collider::Type::Plane);
  Energy energy(m);
  std::fill(energy.fixed.begin(), energy.fixed.end(), 1);
  const std::vector<double> y = positions(m);
  std::vector<double> g;
  EXPECT_EQ(energy(m, y, &g), 0.0);
  for (double gi : g) EXPECT_EQ(gi, 0.0);
  m.colliders.clear();
  Energy none(m);
  EXPECT_EQ(none.term.colliders(), 0);
  EXPECT_EQ(none.term.perVertex(), nullptr);
  EXPECT_EQ(none(m, y, &g), 0.0);
}

}  // namespace
}  // namespace galsculpt

#include "solver/frame/step.h"

#include <gtest/gtest.h>

#include "solver/frame/parallel.h"
#include "solver/mesh/shape_generators.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

// A 2x2x8 bar of cubes (6 tets each) along y, 10 cm per cube.
TetMesh bar(int nx = 2, int ny = 8, int nz = 2, double size = 0.1) {
  return test::gridBar(nx, ny, nz, size);
}

MaterialParams rubber(MaterialModel model = MaterialModel::StableNeoHookean, double e = 1e5,
                      double nu = 0.4) {
  return {model, lameFromYoungPoisson(e, nu), 1000.0, {}};
}

AnchorConstraint topAnchor(const SimModel& m) {
  AnchorConstraint a;
  const double top = boundingBox(m.mesh.vertices).max.y();
  for (int v = 0; v < m.numVertices(); ++v) {
    if (m.mesh.vertices[v].y() > top - 1e-9) a.vertices.push_back(v);
  }
  return a;
}

double kineticEnergy(const SimModel& m, const SimState& s) {
  double k = 0.0;
  for (int v = 0; v < m.numVertices(); ++v) k += 0.5 * m.mass[v] * s.v[v].squaredNorm();
  return k;
}

TEST(Step, AssembledStiffnessIsTheSumOfElementMatrices) {
  const SimModel m = buildSimModel(bar(1, 2, 1), rubber());
  SimState s = initialState(m);
  for (int v = 0; v < m.numVertices(); ++v)
    s.x[v] += 0.01 * Vec3(std::sin(v), std::cos(3 * v), std::sin(5 * v));
  Eigen::VectorXd g;
  BlockSparseMatrix k(m.pattern);
  assembleElastic(m, s.x, s, g, &k);
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(3 * m.numVertices(), 3 * m.numVertices());
  for (int t = 0; t < m.numTets(); ++t) {
    const Tet& tet = m.mesh.tets[t];
    ElementEval e;
    evaluateElement(m.material.model, m.material.lame, m.rest[t],
                    {s.x[tet[0]], s.x[tet[1]], s.x[tet[2]], s.x[tet[3]]}, EdgeDamage{},
                    HessianMode::ProjectedSpd, e);
    for (int a = 0; a < 4; ++a) {
      for (int b = 0; b < 4; ++b)
        dense.block<3, 3>(3 * tet[a], 3 * tet[b]) += e.hessian.block<3, 3>(3 * a, 3 * b);
    }
  }
  const Eigen::MatrixXd assembled = Eigen::MatrixXd(k.toEigen());
  EXPECT_LT((assembled - dense).norm(), 1e-9 * dense.norm());
  EXPECT_LT((assembled - assembled.transpose()).norm(), 1e-9 * dense.norm());
}

TEST(Step, TheGradientOverAFewVerticesIsTheAssembledGradientsSumThere) {
  const SimModel m = buildSimModel(bar(2, 4, 2), rubber());
  SimState s = initialState(m);
  for (int v = 0; v < m.numVertices(); ++v)
    s.x[v] += 0.01 * Vec3(std::sin(v), std::cos(3 * v), std::sin(5 * v));
  for (int e = 0; e < m.numEdges(); e += 7) s.damaged[e] = 1;  // cracked elements too
  Eigen::VectorXd g;
  assembleElastic(m, s.x, s, g, nullptr);
  std::vector<int> vertices = topAnchor(m).vertices;
  vertices.push_back(m.numVertices() / 2);
  vertices.push_back(vertices.front());  // listed twice, counted once
  Vec3 expected = Vec3::Zero();
  for (size_t i = 0; i + 1 < vertices.size(); ++i) expected += g.segment<3>(3 * vertices[i]);
  const Vec3 sum = elasticGradientSum(m, s.x, s, vertices);
  ASSERT_GT(expected.norm(), 1.0);
  EXPECT_LT((sum - expected).norm(), 1e-9 * expected.norm());
}

TEST(Step, FreeFallIsExactForARigidBody) {
  const SimModel m = buildSimModel(bar(1, 2, 1), rubber());
  SimState s = initialState(m);
  StepSettings settings;
  settings.dt = 0.01;
  step(m, s, settings);
  for (int v = 0; v < m.numVertices(); ++v) {
    EXPECT_NEAR(s.v[v].y(), -9.81 * 0.01, 1e-9);
    EXPECT_NEAR(s.x[v].y() - m.mesh.vertices[v].y(), -9.81 * 1e-4, 1e-9);
  }
}

// Without gravity the residual is still measured against a weight (what the body would weigh
// under 1 g); it once divided by almost nothing and read 1e12 for a well-solved frame.
TEST(Step, ResidualStaysMeaningfulWithoutGravity) {
  SimModel m = buildSimModel(bar(), rubber());
  m.gravity = Vec3::Zero();
  const StepSettings base;
  AnchorConstraint pulled = topAnchor(m);
  pulled.path = {{0.0, Vec3::Zero()}, {1.0, Vec3(0.0, 0.05, 0.0)}};
  SimState ref = initialState(m);
  ref.anchors = {pulled};
  const StepReport r = step(m, ref, referenceSettings(base));
  EXPECT_LT(r.residual, 1e-6) << "Newton converged";
  SimState one = initialState(m);
  one.anchors = {pulled};
  const StepReport linear = step(m, one, base);
  EXPECT_GT(linear.residual, 0.0);
  EXPECT_LT(linear.residual, 10.0) << "one linearized step is close, relative to 1 g";
}

TEST(Step, ReferenceNewtonConvergesAndAgreesWithManyLinearizedSubsteps) {
  const SimModel m = buildSimModel(bar(), rubber());
  StepSettings base;
  base.dt = 1.0 / 60.0;
  SimState ref = initialState(m);
  ref.anchors = {topAnchor(m)};
  const StepReport r = step(m, ref, referenceSettings(base));
  EXPECT_LT(r.residual, 1e-8);
  EXPECT_GT(r.newtonIterations, 1);
  // Tiny linearized sub-steps approach the same trajectory point.
  StepSettings fine = base;
  fine.substeps = 64;
  SimState lin = initialState(m);
  lin.anchors = ref.anchors;
  step(m, lin, fine);
  double maxDiff = 0.0, maxMove = 0.0;
  for (int v = 0; v < m.numVertices(); ++v) {
    maxDiff = std::max(maxDiff, (lin.x[v] - ref.x[v]).norm());
    maxMove = std::max(maxMove, (ref.x[v] - m.mesh.vertices[v]).norm());
  }
  EXPECT_GT(maxMove, 0.0);
  // Different schemes (one big implicit step vs many small ones): agree to first order in dt.
  EXPECT_LT(maxDiff, 0.5 * maxMove);
}

TEST(Step, HangingBarSettlesIntoStaticEquilibrium) {
  MaterialParams material = rubber(MaterialModel::StableNeoHookean, 2e5, 0.45);
  material.dampingMass = 5.0;
  const SimModel m = buildSimModel(bar(), material);
  SimState s = initialState(m);
  s.anchors = {topAnchor(m)};
  const StepSettings settings = referenceSettings(StepSettings{});
  for (int f = 0; f < 120; ++f) step(m, s, settings);
  EXPECT_LT(kineticEnergy(m, s), 1e-7 * 32.0 * 9.81 * 0.8) << "at rest: a tiny fraction of m g L";
  // Static balance on the free vertices: elastic force equals weight.
  Eigen::VectorXd g;
  assembleElastic(m, s.x, s, g, nullptr);
  double weight = 0.0, imbalance = 0.0;
  std::vector<char> fixed(m.numVertices(), 0);
  for (int v : s.anchors[0].vertices) fixed[v] = 1;
  for (int v = 0; v < m.numVertices(); ++v) {
    if (fixed[v]) continue;
    weight += m.mass[v] * 9.81;
    imbalance += (g.segment<3>(3 * v) - m.mass[v] * Vec3(0, -9.81, 0)).norm();
  }
  EXPECT_LT(imbalance, 1e-3 * weight);
}

TEST(Step, DeterministicAcrossThreadCounts) {
  const SimModel m = buildSimModel(bar(), rubber());
  const StepSettings settings;
  auto run = [&](int threads) {
    setThreadCount(threads);
    SimState s = initialState(m);
    s.anchors = {topAnchor(m)};
    for (int f = 0; f < 5; ++f) step(m, s, settings);
    return s.x;
  };
  const auto one = run(1);
  const auto two = run(2);
  setThreadCount(0);
  for (size_t v = 0; v < one.size(); ++v) EXPECT_EQ(one[v], two[v]);
}

TEST(Step, AnchorsFollowTheirPath) {
  const SimModel m = buildSimModel(bar(1, 2, 1), rubber());
  SimState s = initialState(m);
  StepSettings settings;
  AnchorConstraint a = topAnchor(m);
  a.path = {{0.0, Vec3::Zero()}, {1.0, Vec3(0.3, 0, 0)}};
  s.anchors = {a};
  settings.dt = 0.1;
  for (int f = 0; f < 5; ++f) step(m, s, settings);
  for (int v : a.vertices) EXPECT_NEAR(s.x[v].x() - m.mesh.vertices[v].x(), 0.15, 1e-12);
  EXPECT_NEAR(anchorOffset(a, 7.0).x(), 0.3, 1e-15) << "held after the last key";
}

// Hard cases: no NaN, bounded energy, and the step recovers instead of failing.
struct HardCase {
  const char* name;
  MaterialParams material;
  double dt;
  double scale;
  double gravityFactor;
};

void PrintTo(const HardCase& c, std::ostream* os) {
  *os << c.name;
}

class StepHardCases : public ::testing::TestWithParam<HardCase> {};

TEST_P(StepHardCases, StayFiniteAndBounded) {
  const HardCase& c = GetParam();
  TetMesh mesh = bar(2, 4, 2, 0.1 * c.scale);
  MaterialParams material = c.material;
  material.dampingMass = 1.0;
  SimModel m = buildSimModel(mesh, material);
  m.gravity = Vec3(0, -9.81 * c.gravityFactor, 0);
  SimState s = initialState(m);
  s.anchors = {topAnchor(m)};
  StepSettings settings;
  settings.dt = c.dt;
  // With fixed anchors nothing does work on the body: backward Euler may only lose energy.
  // Total energy = kinetic + elastic + gravitational potential; it must never grow.
  auto totalEnergy = [&](double elastic) {
    double e = kineticEnergy(m, s) + elastic;
    for (int v = 0; v < m.numVertices(); ++v) e -= m.mass[v] * m.gravity.dot(s.x[v]);
    return e;
  };
  const double start = totalEnergy(0.0);
  double scale = 0.0;
  for (int v = 0; v < m.numVertices(); ++v) scale += m.mass[v] * m.gravity.norm() * 0.4 * c.scale;
  for (int f = 0; f < 30; ++f) {
    const StepReport r = step(m, s, settings);
    for (const Vec3& x : s.x) ASSERT_TRUE(x.allFinite()) << c.name << " frame " << f;
    ASSERT_LT(totalEnergy(r.elasticEnergy), start + 1e-6 * scale) << c.name << " frame " << f;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Cases, StepHardCases,
    ::testing::Values(
        HardCase{"nu_0499", rubber(MaterialModel::StableNeoHookean, 1e5, 0.499), 1.0 / 60, 1.0,
                 1.0},
        HardCase{"steel_dt_30",
                 {MaterialModel::Corotational, lameFromYoungPoisson(2e11, 0.3), 7850, {}},
                 1.0 / 30,
                 1.0,
                 1.0},
        HardCase{"stvk_huge_load", rubber(MaterialModel::StVK, 1e5, 0.4), 1.0 / 60, 1.0, 1e6},
        HardCase{"snh_huge_load", rubber(MaterialModel::StableNeoHookean, 1e5, 0.4), 1.0 / 60, 1.0,
                 1e6},
        HardCase{"millimetre_scale", rubber(), 1.0 / 60, 1e-3, 1.0},
        HardCase{"kilometre_scale", rubber(), 1.0 / 60, 1e3, 1.0}),
    [](const auto& info) { return std::string(info.param.name); });

TEST(Step, InvertedAndSliverElementsRecover) {
  TetMesh mesh = bar(1, 2, 1);
  // Push one interior-ish vertex through its neighbours: several tets start inverted.
  MaterialParams material = rubber();
  material.dampingMass = 2.0;
  const SimModel m = buildSimModel(mesh, material);
  SimState s = initialState(m);
  s.x[4] += Vec3(0.25, 0.0, 0.0);
  s.x[5] = s.x[4] + Vec3(1e-4, 1e-4, 0.0);  // and a near-sliver neighbour
  s.anchors = {topAnchor(m)};
  const StepSettings settings;
  for (int f = 0; f < 60; ++f) {
    const StepReport r = step(m, s, settings);
    for (const Vec3& x : s.x) ASSERT_TRUE(x.allFinite());
    ASSERT_LE(r.retries, settings.maxRetries + 1);
  }
  double inverted = 0;
  for (int t = 0; t < m.numTets(); ++t) {
    const Tet& tet = m.mesh.tets[t];
    inverted += tetSixVolume(s.x[tet[0]], s.x[tet[1]], s.x[tet[2]], s.x[tet[3]]) < 0;
  }
  EXPECT_EQ(inverted, 0) << "stable neo-Hookean pushes inverted elements back";
}

TEST(Step, FullyDamagedElementAndIsolatedVertexFallFreely) {
  TetMesh mesh = bar(1, 2, 1);
  mesh.vertices.push_back(Vec3(5, -5, 5));  // a vertex in no tet
  const SimModel m = buildSimModel(mesh, rubber());
  SimState s = initialState(m);
  for (int e = 0; e < 6; ++e) s.damaged[m.tetEdges[0][e]] = 1;  // one element fully damaged
  s.anchors = {topAnchor(m)};
  const StepSettings settings;
  for (int f = 0; f < 10; ++f) step(m, s, settings);
  const int isolated = m.numVertices() - 1;
  EXPECT_NEAR(s.v[isolated].y(), -9.81 * 10.0 / 60.0, 1e-9) << "a free particle under gravity";
  for (const Vec3& x : s.x) EXPECT_TRUE(x.allFinite());
  EXPECT_EQ(countDamagePieces(m, s), 2) << "the bar and the isolated vertex";
}

}  // namespace
}  // namespace galsculpt

namespace galsculpt {
namespace {

TEST(StepContact, ABlockRestsOnTheGroundAndTheContactForceIsItsWeight) {
  TetMesh mesh = bar(2, 2, 2);
  for (Vec3& v : mesh.vertices) v.y() += 0.05;  // starts 5 cm above the ground
  MaterialParams material = rubber(MaterialModel::StableNeoHookean, 1e5, 0.3);
  material.dampingMass = 4.0;
  SimModel m = buildSimModel(mesh, material);
  m.colliders.push_back(Collider{});  // ground plane y = 0
  SimState s = initialState(m);
  const StepSettings settings;
  StepReport r;
  for (int f = 0; f < 180; ++f) r = step(m, s, settings);
  double totalMass = 0.0, lowest = 1e9;
  for (int v = 0; v < m.numVertices(); ++v) {
    totalMass += m.mass[v];
    lowest = std::min(lowest, s.x[v].y());
  }
  EXPECT_GT(lowest, -2e-3) << "penetration stays small";
  EXPECT_LT(lowest, 1e-3) << "and it did land";
  ASSERT_EQ(r.contactForces.size(), 1u);
  EXPECT_NEAR(r.contactForces[0].y(), totalMass * 9.81, 0.02 * totalMass * 9.81);
}

TEST(StepPlasticity, ClayKeepsADentAndRubberDoesNot) {
  auto dent = [](bool clay) {
    MaterialParams material = rubber(MaterialModel::StVK, 2e5, 0.3);
    if (clay) material.plastic = {5e3, 1e4};
    material.dampingMass = 5.0;
    SimModel m = buildSimModel(bar(2, 2, 2), material);
    m.gravity = Vec3::Zero();
    SimState s = initialState(m);
    // Press the top face down by 4 cm over half a second, hold, then let go.
    AnchorConstraint bottom, press;
    for (int v = 0; v < m.numVertices(); ++v) {
      if (m.mesh.vertices[v].y() < 1e-9) bottom.vertices.push_back(v);
      if (m.mesh.vertices[v].y() > 0.2 - 1e-9) press.vertices.push_back(v);
    }
    press.path = {{0.0, Vec3::Zero()}, {0.5, Vec3(0, -0.04, 0)}};
    const StepSettings settings;
    s.anchors = {bottom, press};
    for (int f = 0; f < 45; ++f) step(m, s, settings);
    s.anchors = {bottom};
    for (int f = 0; f < 240; ++f) step(m, s, settings);
    double top = 0.0;
    for (int v : press.vertices) top += s.x[v].y();
    return 0.2 - top / press.vertices.size();  // remaining dent depth
  };
  EXPECT_GT(dent(true), 0.02) << "clay keeps most of the 4 cm";
  EXPECT_LT(std::abs(dent(false)), 2e-3) << "rubber springs back";
}

}  // namespace
}  // namespace galsculpt

namespace galsculpt {
namespace {

// A sub-step that cannot succeed (a NaN velocity poisons every attempt) is rolled back and
// halved up to maxRetries times, each counted; then the frame is given up, the state kept as it
// was and time moved on, so that a caller is never stuck in a loop.
TEST(StepRecovery, FailedSubstepsAreRolledBackCountedAndNeverHang) {
  const SimModel m = buildSimModel(bar(1, 2, 1), rubber());
  SimState s = initialState(m);
  s.v[3] = Vec3(std::nan(""), 0, 0);
  const std::vector<Vec3> before = s.x;
  StepSettings settings;
  settings.maxRetries = 3;
  const StepReport r = step(m, s, settings);
  EXPECT_EQ(r.retries, settings.maxRetries + 1);
  EXPECT_NEAR(s.time, settings.dt, 1e-15);
  EXPECT_EQ(s.x, before) << "the positions are those of the last good state";
}

}  // namespace
}  // namespace galsculpt

#include "solver/fem/tet_element.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "solver/fem/material_table.h"

namespace galsculpt {
namespace {

const Lame kLame = lameFromYoungPoisson(1e5, 0.4);
// Every model of the table (solver/fem/material_table.h).
std::vector<MaterialModel> allModels() {
  std::vector<MaterialModel> out;
  for (const MaterialInfo& row : kMaterialModels) out.push_back(row.model);
  return out;
}
const std::vector<MaterialModel> kModels = allModels();

TetPoints restTet() {
  return {Eigen::Vector3d(0.0, 0.0, 0.0), Eigen::Vector3d(1.0, 0.1, 0.0),
          Eigen::Vector3d(0.2, 0.9, 0.1), Eigen::Vector3d(0.1, 0.2, 1.1)};
}

TetPoints deformed(const TetPoints& rest, double amount, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-amount, amount);
  TetPoints x = rest;
  for (auto& p : x) p += Eigen::Vector3d(u(gen), u(gen), u(gen));
  return x;
}

Vec12 flat(const TetPoints& x) {
  Vec12 v;
  for (int i = 0; i < 4; ++i) v.segment<3>(3 * i) = x[i];
  return v;
}

TetPoints unflat(const Vec12& v) {
  TetPoints x;
  for (int i = 0; i < 4; ++i) x[i] = v.segment<3>(3 * i);
  return x;
}

ElementEval eval(MaterialModel m, const TetRest& r, const TetPoints& x, EdgeDamage d,
                 HessianMode mode) {
  ElementEval out;
  evaluateElement(m, kLame, r, x, d, mode, out);
  return out;
}

// Central differences of the energy (gradient) and of the gradient (Hessian) at x, step h.
void finiteDifferences(MaterialModel m, const TetRest& r, const TetPoints& x, EdgeDamage d,
                       double h, Vec12& gradient, Mat12& hessian) {
  for (int i = 0; i < 12; ++i) {
    Vec12 plus = flat(x), minus = flat(x);
    plus[i] += h;
    minus[i] -= h;
    const ElementEval ep = eval(m, r, unflat(plus), d, HessianMode::None);
    const ElementEval em = eval(m, r, unflat(minus), d, HessianMode::None);
    gradient[i] = (ep.energy - em.energy) / (2 * h);
    hessian.col(i) = (ep.gradient - em.gradient) / (2 * h);
  }
}

struct Case {
  MaterialModel model;
  EdgeDamage damage;
};

std::vector<Case> allCases() {
  std::vector<Case> cases;
  for (MaterialModel m : kModels) cases.push_back({m, EdgeDamage{}});
  for (std::uint8_t mask : {0x3e, 0x38, 0x15, 0x00, 0x21, 0x0c}) {
    for (bool resists : {true, false})
      cases.push_back({MaterialModel::StVK, EdgeDamage{mask, resists}});
  }
  return cases;
}

// Central differences of the energy give the gradient; of the gradient, the exact Hessian.
TEST(TetElement, GradientAndHessianMatchFiniteDifferences) {
  const TetPoints rest = restTet();
  const TetRest r = computeTetRest(rest);
  for (const Case& c : allCases()) {
    for (unsigned seed = 1; seed <= 4; ++seed) {
      SCOPED_TRACE(::testing::Message() << "model " << static_cast<int>(c.model) << " mask "
                                        << static_cast<int>(c.damage.intact) << " seed " << seed);
      const TetPoints x = deformed(rest, 0.3, seed);
      const ElementEval e = eval(c.model, r, x, c.damage, HessianMode::Exact);
      Vec12 fdGradient;
      Mat12 fdHessian;
      finiteDifferences(c.model, r, x, c.damage, 1e-6, fdGradient, fdHessian);
      const double gScale = std::max(1.0, e.gradient.norm());
      EXPECT_LT((fdGradient - e.gradient).norm(), 1e-6 * gScale);
      const double hScale = std::max(1.0, e.hessian.norm());
      EXPECT_LT((fdHessian - e.hessian).norm(), 1e-5 * hScale);
      EXPECT_LT((e.hessian - e.hessian.transpose()).norm(), 1e-9 * hScale);
    }
  }
}

TEST(TetElement, RestStateHasNoEnergyAndNoForce) {
  const TetPoints rest = restTet();
  const TetRest r = computeTetRest(rest);
  for (const Case& c : allCases()) {
    const ElementEval e = eval(c.model, r, rest, c.damage, HessianMode::None);
    EXPECT_NEAR(e.energy, 0.0, 1e-9);
    EXPECT_LT(e.gradient.norm(), 1e-8);
  }
}

TEST(TetElement, RigidMotionsProduceNoForce) {
  const TetPoints rest = restTet();
  const TetRest r = computeTetRest(rest);
  const Eigen::Matrix3d rot =
      Eigen::AngleAxisd(2.1, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
  TetPoints moved;
  for (int i = 0; i < 4; ++i) moved[i] = rot * rest[i] + Eigen::Vector3d(3, -1, 7);
  for (const Case& c : allCases()) {
    const ElementEval e = eval(c.model, r, moved, c.damage, HessianMode::None);
    EXPECT_NEAR(e.energy, 0.0, 1e-7);
    EXPECT_LT(e.gradient.norm(), 1e-6);
  }
}

TEST(TetElement, ProjectedHessianIsPositiveSemidefinite) {
  const TetPoints rest = restTet();
  const TetRest r = computeTetRest(rest);
  for (const Case& c : allCases()) {
    for (unsigned seed = 1; seed <= 20; ++seed) {
      TetPoints x = deformed(rest, 0.6, seed);
      if (seed % 4 == 0) std::swap(x[0], x[1]);  // inverted configurations too
      const ElementEval e = eval(c.model, r, x, c.damage, HessianMode::ProjectedSpd);
      const Eigen::SelfAdjointEigenSolver<Mat12> eig(e.hessian);
      EXPECT_GE(eig.eigenvalues().minCoeff(), -1e-8 * std::max(1.0, e.hessian.norm()));
      EXPECT_TRUE(e.gradient.allFinite());
    }
  }
}

TEST(TetElement, SmallStrainsAgreeWithLinearElasticity) {
  Eigen::Matrix3d h;
  h << 0.3, -0.2, 0.5, 0.1, -0.4, 0.2, 0.6, 0.3, 0.1;
  const double eps = 1e-6;
  const Eigen::Matrix3d strain = 0.5 * eps * (h + h.transpose());
  const Eigen::Matrix3d linear =
      2 * kLame.mu * strain + kLame.lambda * strain.trace() * Eigen::Matrix3d::Identity();
  for (MaterialModel m : kModels) {
    const Eigen::Matrix3d p = firstPiolaStress(m, kLame, Eigen::Matrix3d::Identity() + eps * h);
    EXPECT_LT((p - linear).norm(), 1e-4 * linear.norm()) << static_cast<int>(m);
  }
}

TEST(TetElement, IntactEdgeStrainFormIsExactlyStVK) {
  const TetPoints rest = restTet();
  const TetRest r = computeTetRest(rest);
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const TetPoints x = deformed(rest, 0.4, seed);
    ElementEval graph, plain;
    evaluateEdgeStrainElement(kLame, r, x, EdgeDamage{}, HessianMode::Exact, graph);
    evaluateElement(MaterialModel::StVK, kLame, r, x, EdgeDamage{}, HessianMode::Exact, plain);
    EXPECT_NEAR(graph.energy, plain.energy, 1e-10 * std::abs(plain.energy));
    EXPECT_LT((graph.gradient - plain.gradient).norm(), 1e-9 * plain.gradient.norm());
    EXPECT_LT((graph.hessian - plain.hessian).norm(), 1e-8 * plain.hessian.norm());
  }
}

TEST(TetElement, VertexWithAllEdgesDamagedIsFree) {
  const TetPoints rest = restTet();
  const TetRest r = computeTetRest(rest);
  const EdgeDamage isolated{0x38, true};  // edges 0-1, 0-2, 0-3 damaged
  TetPoints x = deformed(rest, 0.2, 3);
  x[0] = Eigen::Vector3d(-2.0, -2.0, -2.0);  // pulled far away: its edges are stretched
  const ElementEval a = eval(MaterialModel::StableNeoHookean, r, x, isolated, HessianMode::Exact);
  EXPECT_EQ(a.gradient.segment<3>(0).norm(), 0.0) << "receives no force";
  x[0] = Eigen::Vector3d(-3.0, -1.0, -2.5);
  const ElementEval b = eval(MaterialModel::StableNeoHookean, r, x, isolated, HessianMode::Exact);
  EXPECT_EQ(a.gradient, b.gradient) << "exerts no force: the others do not feel it move";
  EXPECT_EQ((a.hessian.block<3, 12>(0, 0).norm()), 0.0);
}

// Every edge damaged: stretched (all six cracks open) the element carries nothing, exactly, in
// every mode (the kernel returns before forming its stiffness); with one edge squeezed shorter
// than at rest its crack closes and pushes back, as the same element did before the short cut.
TEST(TetElement, AnElementWithEveryCrackOpenCarriesNothingExactly) {
  const TetPoints rest = restTet();
  const TetRest r = computeTetRest(rest);
  TetPoints stretched = rest;
  for (Eigen::Vector3d& p : stretched) p *= 1.2;
  for (HessianMode mode : {HessianMode::None, HessianMode::Exact, HessianMode::ProjectedSpd}) {
    const ElementEval e = eval(MaterialModel::StVK, r, stretched, EdgeDamage{0x00, true}, mode);
    EXPECT_EQ(e.energy, 0.0);
    EXPECT_EQ(e.gradient.norm(), 0.0);
    if (mode != HessianMode::None) {
      EXPECT_EQ(e.hessian.norm(), 0.0);
    }
  }
  TetPoints squeezed = stretched;
  squeezed[1] = rest[0] + 0.8 * (rest[1] - rest[0]);  // edge 0-1 shorter than at rest
  const ElementEval e =
      eval(MaterialModel::StVK, r, squeezed, EdgeDamage{0x00, true}, HessianMode::Exact);
  EXPECT_GT(e.energy, 0.0);
  EXPECT_GT(e.gradient.segment<3>(3).dot(rest[0] - rest[1]), 0.0) << "pushes vertex 1 back out";
  Vec12 fdGradient;
  Mat12 fdHessian;
  finiteDifferences(MaterialModel::StVK, r, squeezed, EdgeDamage{0x00, true}, 1e-6, fdGradient,
                    fdHessian);
  EXPECT_LT((fdGradient - e.gradient).norm(), 1e-6 * std::max(1.0, e.gradient.norm()));
  EXPECT_LT((fdHessian - e.hessian).norm(), 1e-5 * std::max(1.0, e.hessian.norm()));
}

// Only edges 0-1 and 2-3 intact: the element holds two pieces, {0, 1} and {2, 3}; stretching
// one must not push the other (the strain coupling between them is removed).
TEST(TetElement, TwoOppositeIntactEdgesAreTwoUncoupledPieces) {
  const TetPoints rest = restTet();
  const TetRest r = computeTetRest(rest);
  const EdgeDamage twoPieces{0x21, false};
  TetPoints x = rest;
  x[1] = rest[0] + 1.3 * (rest[1] - rest[0]);  // piece {0, 1} stretched, {2, 3} at rest
  const ElementEval e = eval(MaterialModel::StVK, r, x, twoPieces, HessianMode::Exact);
  EXPECT_GT(e.gradient.segment<3>(3).norm(), 0.0) << "the stretched edge pulls back";
  EXPECT_EQ(e.gradient.segment<6>(6).norm(), 0.0) << "the other piece feels nothing";
  EXPECT_EQ((e.hessian.block<6, 6>(0, 6).norm()), 0.0) << "no stiffness couples the pieces";
  // The coupling-free stiffness stays positive semi-definite.
  const Eigen::SelfAdjointEigenSolver<Mat12> eig(
      eval(MaterialModel::StVK, r, deformed(rest, 0.3, 2), EdgeDamage{0x21, true},
           HessianMode::ProjectedSpd)
          .hessian);
  EXPECT_GT(eig.eigenvalues().minCoeff(), -1e-9 * eig.eigenvalues().maxCoeff());
}

TEST(TetElement, DamagedEdgesStillResistCompressionUnlessToldNot) {
  const TetPoints rest = restTet();
  const TetRest r = computeTetRest(rest);
  TetPoints squeezed = rest;
  squeezed[1] = rest[0] + 0.5 * (rest[1] - rest[0]);  // edge 0-1 at half length
  const ElementEval resists =
      eval(MaterialModel::StVK, r, squeezed, EdgeDamage{0x3e, true}, HessianMode::None);
  const ElementEval yields =
      eval(MaterialModel::StVK, r, squeezed, EdgeDamage{0x3e, false}, HessianMode::None);
  EXPECT_GT(resists.energy, yields.energy);
  TetPoints stretched = rest;
  stretched[1] = rest[0] + 1.5 * (rest[1] - rest[0]);
  const ElementEval a =
      eval(MaterialModel::StVK, r, stretched, EdgeDamage{0x3e, true}, HessianMode::None);
  const ElementEval b =
      eval(MaterialModel::StVK, r, stretched, EdgeDamage{0x3e, false}, HessianMode::None);
  EXPECT_DOUBLE_EQ(a.energy, b.energy) << "in tension a damaged edge carries nothing either way";
}

// A crack opens where its edge force would turn tensile, not where its own strain changes
// sign. Along a path that pulls vertex 1 from squeezing its damaged edges to stretching them,
// the force must never jump (the energy is C1): each step's change of force stays within what
// the largest stiffness on the path allows. A mask such as min(eps, 0), whose force jumps where
// a crack closes, fails this by orders of magnitude.
TEST(TetElement, ForceIsContinuousWhereACrackOpensOrCloses) {
  const TetPoints rest = restTet();
  const TetRest r = computeTetRest(rest);
  for (std::uint8_t mask : {0x3e, 0x38, 0x15, 0x00, 0x21}) {
    for (unsigned seed = 1; seed <= 3; ++seed) {
      SCOPED_TRACE(::testing::Message() << "mask " << static_cast<int>(mask) << " seed " << seed);
      const EdgeDamage damage{mask, true};
      const TetPoints base = deformed(rest, 0.05, seed);
      const Eigen::Vector3d direction = (rest[1] - rest[0]).normalized();
      const int steps = 4000;
      const double from = -0.15, to = 0.15, h = (to - from) / steps;
      double maxStiffness = 0.0, maxJumpRate = 0.0;
      Vec12 previous;
      for (int i = 0; i <= steps; ++i) {
        TetPoints x = base;
        x[1] += (from + i * h) * direction;
        const ElementEval e = eval(MaterialModel::StVK, r, x, damage, HessianMode::Exact);
        maxStiffness = std::max(maxStiffness, e.hessian.norm());
        if (i > 0) maxJumpRate = std::max(maxJumpRate, (e.gradient - previous).norm() / h);
        previous = e.gradient;
      }
      EXPECT_GT(maxStiffness, 0.0);
      EXPECT_LT(maxJumpRate, 1.5 * maxStiffness);
    }
  }
}

// A damaged element's energy is the least over crack openings c (c >= 0 on damaged edges that
// resist compression, free on the others) of 1/2 (eps - c)^T K (eps - c): no opening does
// better, damaged edges carry no tension, and the energy is convex in the edge strains.
TEST(TetElement, CrackOpeningsMinimizeTheEnergyAndCarryNoTension) {
  const TetRest r = computeTetRest(restTet());
  const kernels::RestData& rest = r;
  double k[6][6];
  kernels::edgeStrainStiffness(kLame, rest, k);
  auto quadratic = [&](const double z[6]) {
    double sum = 0.0;
    for (int a = 0; a < 6; ++a)
      for (int b = 0; b < 6; ++b) sum += 0.5 * z[a] * k[a][b] * z[b];
    return sum;
  };
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> strain(-0.1, 0.1), opening(0.0, 0.1);
  int closedSeen = 0, openedSeen = 0;
  for (std::uint8_t mask : {0x3e, 0x38, 0x15, 0x00, 0x07}) {
    for (bool resists : {true, false}) {
      for (int trial = 0; trial < 200; ++trial) {
        double eps[6], other[6], mid[6];
        for (int e = 0; e < 6; ++e) {
          eps[e] = strain(gen);
          other[e] = strain(gen);
          mid[e] = 0.5 * (eps[e] + other[e]);
        }
        kernels::CrackedStrainState s, so, sm;
        kernels::crackedStrainState(kLame, rest, eps, mask, resists, true, s);
        kernels::crackedStrainState(kLame, rest, other, mask, resists, false, so);
        kernels::crackedStrainState(kLame, rest, mid, mask, resists, false, sm);
        const double scale = std::max(1.0, s.energy);
        EXPECT_LE(sm.energy, 0.5 * (s.energy + so.energy) + 1e-12 * scale) << "convex";
        for (int e = 0; e < 6; ++e) {
          if ((mask >> e) & 1) continue;
          if (resists) {
            EXPECT_LE(s.tau[e], 1e-9 * kLame.mu) << "a damaged edge pushes, never pulls";
            (s.tau[e] < 0.0 ? closedSeen : openedSeen)++;
          } else {
            EXPECT_EQ(s.tau[e], 0.0) << "a damaged edge carries nothing";
          }
        }
        for (int sample = 0; sample < 20; ++sample) {  // feasible openings do no better
          double z[6];
          for (int e = 0; e < 6; ++e) {
            const bool damaged = !((mask >> e) & 1);
            const double c = !damaged ? 0.0 : resists ? opening(gen) : strain(gen);
            z[e] = eps[e] - c;
          }
          EXPECT_GE(quadratic(z), s.energy - 1e-12 * scale);
        }
        // Energy and edge forces agree: central differences of the energy in each strain.
        for (int e = 0; e < 6; ++e) {
          const double h = 1e-7;
          double plus[6], minus[6];
          for (int m = 0; m < 6; ++m) plus[m] = minus[m] = eps[m];
          plus[e] += h;
          minus[e] -= h;
          kernels::CrackedStrainState sp, sn;
          kernels::crackedStrainState(kLame, rest, plus, mask, resists, false, sp);
          kernels::crackedStrainState(kLame, rest, minus, mask, resists, false, sn);
          EXPECT_NEAR((sp.energy - sn.energy) / (2 * h), s.tau[e], 1e-6 * kLame.mu);
        }
      }
    }
  }
  EXPECT_GT(closedSeen, 100) << "the samples close cracks";
  EXPECT_GT(openedSeen, 100) << "and open them";
}

TEST(TetElement, InvertedStableNeoHookeanStaysFiniteAndPushesBack) {
  const TetPoints rest = restTet();
  const TetRest r = computeTetRest(rest);
  TetPoints inverted = rest;
  inverted[3] = Eigen::Vector3d(0.3, 0.3, -0.5);  // through the opposite face
  EXPECT_LT(deformationGradient(r, inverted).determinant(), 0.0);
  const ElementEval e =
      eval(MaterialModel::StableNeoHookean, r, inverted, EdgeDamage{}, HessianMode::ProjectedSpd);
  EXPECT_TRUE(std::isfinite(e.energy));
  EXPECT_TRUE(e.gradient.allFinite());
  EXPECT_TRUE(e.hessian.allFinite());
  // The force on vertex 3 points back towards its rest side (+z).
  EXPECT_LT(e.gradient[11], 0.0);
}

// The edge projection includes the shear terms with their factor 2 (paper eq. 1 drops it).
TEST(TetElement, EdgeNormalStressIsTheFullProjection) {
  const TetPoints rest = restTet();
  const TetRest r = computeTetRest(rest);
  const TetPoints x = deformed(rest, 0.1, 9);
  const Eigen::Matrix3d f = deformationGradient(r, x);
  for (MaterialModel m : kModels) {
    const Eigen::Matrix3d s = firstPiolaStress(m, kLame, f) * f.transpose() / f.determinant();
    const std::array<double, 6> stress = edgeNormalStress(m, kLame, r, x, EdgeDamage{});
    for (int e = 0; e < 6; ++e) {
      const Eigen::Vector3d n = (x[kTetEdges[e][1]] - x[kTetEdges[e][0]]).normalized();
      const double expected = s(0, 0) * n.x() * n.x() + s(1, 1) * n.y() * n.y() +
                              s(2, 2) * n.z() * n.z() + 2 * s(0, 1) * n.x() * n.y() +
                              2 * s(0, 2) * n.x() * n.z() + 2 * s(1, 2) * n.y() * n.z();
      EXPECT_NEAR(stress[e], expected, 1e-9 * s.norm());
    }
  }
}

TEST(TetElement, UniaxialTensionLoadsTheAlignedEdgeOnly) {
  // A right-corner tet stretched along x: sigma = diag(sxx, 0, 0) for a material with nu = 0.
  const Lame noPoisson = lameFromYoungPoisson(1e6, 0.0);
  const TetPoints rest = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0),
                          Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(0, 0, 1)};
  const TetRest r = computeTetRest(rest);
  TetPoints x = rest;
  x[1].x() = 1.001;
  const std::array<double, 6> s =
      edgeNormalStress(MaterialModel::Corotational, noPoisson, r, x, EdgeDamage{});
  EXPECT_NEAR(s[0], 1e6 * 0.001, 2.0);  // edge 0-1 along x: E * strain
  EXPECT_NEAR(s[1], 0.0, 1e-6);         // edge 0-2 along y
  EXPECT_NEAR(s[3], 0.5 * s[0], 2.0);   // edge 1-2 at 45 degrees: cos^2 = 1/2
}

}  // namespace
}  // namespace galsculpt

// The smooth crack-closure law (solver/fem/crack_law.h) and the damaged element it shapes
// (element_kernels.h, addSmoothCrackEnergy): the barrier's derivatives, the element's forces and
// stiffness against finite differences, no force at rest, faces that press in by less than the
// width, convexity, and the hard law as the width goes to zero.
#include "solver/fem/crack_law.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "solver/fem/element_kernels.h"
#include "solver/fem/tet_element.h"

namespace galsculpt {
namespace {

Lame lameWithWidth(double width) {
  Lame lame = lameFromYoungPoisson(1e5, 0.4);
  lame.crackWidth = width;
  return lame;
}

TetPoints restTet() {
  return {Eigen::Vector3d(0.0, 0.0, 0.0), Eigen::Vector3d(1.0, 0.1, 0.0),
          Eigen::Vector3d(0.2, 0.9, 0.1), Eigen::Vector3d(0.1, 0.2, 1.1)};
}

// Damage masks (bit set: intact) that leave one-way edges: single cracks, a face's three
// edges, two pieces, and every edge damaged.
constexpr std::uint8_t kMasks[] = {0x3e, 0x38, 0x15, 0x21, 0x0c, 0x00};

kernels::CrackedStrainState strainState(const Lame& lame, const kernels::RestData& rest,
                                        const double eps[6], std::uint8_t intact,
                                        bool wantStiffness) {
  kernels::CrackedStrainState s;
  kernels::crackedStrainState(lame, rest, eps, intact, true, wantStiffness, s);
  return s;
}

TEST(CrackLaw, BarrierShapeIsFlatAtContactAndItsDerivativesAreExact) {
  const kernels::CrackBarrier zero = kernels::crackBarrierShape(0.0);
  EXPECT_EQ(zero.value, 0.0);
  EXPECT_EQ(zero.slope, 0.0);
  EXPECT_EQ(zero.curvature, 0.0);
  const kernels::CrackBarrier apart = kernels::crackBarrierShape(-0.3);
  EXPECT_EQ(apart.value + apart.slope + apart.curvature, 0.0) << "faces apart feel nothing";
  for (double s : {1e-3, 0.05, 0.3, 0.6, 0.9, 0.99}) {
    const double h = 1e-6 * (1.0 - s);
    const kernels::CrackBarrier b = kernels::crackBarrierShape(s);
    const kernels::CrackBarrier plus = kernels::crackBarrierShape(s + h);
    const kernels::CrackBarrier minus = kernels::crackBarrierShape(s - h);
    EXPECT_NEAR((plus.value - minus.value) / (2 * h), b.slope, 1e-6 * std::max(1.0, b.slope));
    EXPECT_NEAR((plus.slope - minus.slope) / (2 * h), b.curvature,
                1e-6 * std::max(1.0, b.curvature));
    EXPECT_GT(b.curvature, 0.0) << "convex";
  }
  EXPECT_GT(kernels::crackBarrierShape(1.0 - 1e-9).value, 1e7) << "unbounded at the width";
  // g in the opening c: the chain rule through s = -c / w.
  const double kappa = 3e4, width = 2e-3;
  for (double c : {-1e-4, -1e-3, -1.9e-3}) {
    const double h = 1e-9;
    const kernels::CrackBarrier g = kernels::crackBarrier(c, kappa, width);
    const kernels::CrackBarrier plus = kernels::crackBarrier(c + h, kappa, width);
    const kernels::CrackBarrier minus = kernels::crackBarrier(c - h, kappa, width);
    EXPECT_LT(g.slope, 0.0) << "pushes the faces apart";
    EXPECT_NEAR((plus.value - minus.value) / (2 * h), g.slope, 1e-6 * std::fabs(g.slope));
    EXPECT_NEAR((plus.slope - minus.slope) / (2 * h), g.curvature, 1e-5 * g.curvature);
  }
}

// Edge forces are the energy's gradient in the six edge strains and the stiffness is the
// forces' Jacobian, by central differences, wherever the law presses faces together.
TEST(CrackLaw, ElementForcesAndStiffnessMatchFiniteDifferences) {
  const TetRest tet = computeTetRest(restTet());
  const kernels::RestData& rest = tet;
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> strain(-0.02, 0.01);
  int pressedSeen = 0;
  for (double width : {1e-3, 1e-2}) {
    const Lame lame = lameWithWidth(width);
    for (std::uint8_t mask : kMasks) {
      for (int trial = 0; trial < 40; ++trial) {
        SCOPED_TRACE(::testing::Message() << "width " << width << " mask " << int(mask));
        double eps[6];
        for (double& e : eps) e = strain(gen);
        const kernels::CrackedStrainState s = strainState(lame, rest, eps, mask, true);
        if (s.unloaded) continue;
        bool pressed = false;
        for (int e = 0; e < 6; ++e) pressed |= !((mask >> e) & 1) && eps[e] - s.z[e] < 0.0;
        pressedSeen += pressed;
        const double h = 1e-7 * width;
        for (int e = 0; e < 6; ++e) {
          double plus[6], minus[6];
          std::copy(eps, eps + 6, plus);
          std::copy(eps, eps + 6, minus);
          plus[e] += h;
          minus[e] -= h;
          const kernels::CrackedStrainState sp = strainState(lame, rest, plus, mask, false);
          const kernels::CrackedStrainState sn = strainState(lame, rest, minus, mask, false);
          const double force = (sp.energy - sn.energy) / (2 * h);
          const double forceScale = std::max(1e-3 * lame.mu, std::fabs(s.tau[e]));
          EXPECT_NEAR(force, s.tau[e], 1e-5 * forceScale) << "edge " << e;
          for (int r = 0; r < 6; ++r) {
            const double column = (sp.tau[r] - sn.tau[r]) / (2 * h);
            EXPECT_NEAR(column, s.stiffness[r][e], 1e-4 * lame.mu + 1e-4 * std::fabs(column))
                << "stiffness " << r << "," << e;
          }
        }
      }
    }
  }
  EXPECT_GT(pressedSeen, 50) << "the samples press crack faces together";
}

// The twelve-coordinate element under the smooth law: gradient and exact Hessian against
// central differences of the energy and of the gradient.
TEST(CrackLaw, TetGradientAndHessianMatchFiniteDifferences) {
  const TetPoints rest = restTet();
  const TetRest tet = computeTetRest(rest);
  const Lame lame = lameWithWidth(5e-3);
  std::mt19937 gen(3);
  std::uniform_real_distribution<double> u(-0.01, 0.01);
  for (std::uint8_t mask : kMasks) {
    for (int trial = 0; trial < 6; ++trial) {
      SCOPED_TRACE(::testing::Message() << "mask " << int(mask) << " trial " << trial);
      TetPoints x = rest;
      for (auto& p : x) p = 0.985 * p + Eigen::Vector3d(u(gen), u(gen), u(gen));  // squeezed
      const EdgeDamage damage{mask, true};
      ElementEval e;
      evaluateElement(MaterialModel::StVK, lame, tet, x, damage, HessianMode::Exact, e);
      const double h = 1e-7;
      for (int i = 0; i < 12; ++i) {
        TetPoints plus = x, minus = x;
        plus[i / 3][i % 3] += h;
        minus[i / 3][i % 3] -= h;
        ElementEval ep, em;
        evaluateElement(MaterialModel::StVK, lame, tet, plus, damage, HessianMode::None, ep);
        evaluateElement(MaterialModel::StVK, lame, tet, minus, damage, HessianMode::None, em);
        EXPECT_NEAR((ep.energy - em.energy) / (2 * h), e.gradient[i],
                    1e-5 * (1.0 + e.gradient.norm()));
        const Vec12 column = (ep.gradient - em.gradient) / (2 * h);
        EXPECT_LT((column - e.hessian.col(i)).norm(), 1e-4 * (1.0 + e.hessian.norm()))
            << "column " << i;
      }
    }
  }
}

// Crack faces at rest, or just touching, feel nothing: no force, no energy, nothing to drift by.
TEST(CrackLaw, CrackAtRestCarriesNothing) {
  const TetRest tet = computeTetRest(restTet());
  const Lame lame = lameWithWidth(1e-2);
  const double zero[6] = {};
  for (std::uint8_t mask : kMasks) {
    const kernels::CrackedStrainState s = strainState(lame, tet, zero, mask, true);
    EXPECT_EQ(s.energy, 0.0) << int(mask);
    for (int e = 0; e < 6; ++e) EXPECT_EQ(s.tau[e], 0.0) << int(mask) << " edge " << e;
  }
}

// However hard a slit is pressed shut, its faces pass into each other by less than the width:
// the openings c = eps - z of the damaged edges stay above -w, and the law then pushes back
// harder than the hard law's whole stiffness would.
TEST(CrackLaw, PressedFacesPenetrateLessThanTheWidth) {
  const TetRest tet = computeTetRest(restTet());
  for (double width : {1e-3, 1e-2}) {
    const Lame smooth = lameWithWidth(width), hard = lameWithWidth(0.0);
    for (std::uint8_t mask : kMasks) {
      for (double squeeze : {1e-3, 1e-2, 0.1, 0.4}) {
        double eps[6];
        for (int e = 0; e < 6; ++e) eps[e] = -squeeze * (1.0 + 0.1 * e);
        const kernels::CrackedStrainState s = strainState(smooth, tet, eps, mask, false);
        const kernels::CrackedStrainState rigid = strainState(hard, tet, eps, mask, false);
        // The openings themselves, from the opening problem the element solves (in an element
        // of two pieces, the intact edges enter it free).
        double k[6][6];
        kernels::edgeStrainStiffness(smooth, tet, k);
        const std::uint8_t damaged = static_cast<std::uint8_t>(~mask & kernels::kIntact);
        const std::uint8_t free = kernels::holdsTwoPieces(mask) ? mask : 0;
        kernels::CrackedStrainState openings{};
        kernels::addOpenedCrackEnergy(k, eps, free, damaged, width, false, openings);
        for (int e = 0; e < 6; ++e) {
          if ((mask >> e) & 1) continue;
          const double opening = eps[e] + kernels::kCrackClosingStrain - openings.z[e];
          EXPECT_GT(opening, -width) << "mask " << int(mask) << " squeeze " << squeeze;
          EXPECT_LT(opening, 0.0) << "pressed shut";
          EXPECT_LE(s.tau[e], 0.0) << "a crack pushes, never pulls";
        }
        EXPECT_LE(s.energy, rigid.energy * (1.0 + 1e-12)) << "softer than the hard law";
        EXPECT_GT(s.energy, 0.0);
      }
    }
  }
}

// The element's energy stays convex in the edge strains, and tends to the hard law's as the
// width goes to zero (the gap shrinking with the width).
TEST(CrackLaw, EnergyIsConvexAndTheHardLawIsItsLimit) {
  const TetRest tet = computeTetRest(restTet());
  std::mt19937 gen(5);
  std::uniform_real_distribution<double> strain(-0.05, 0.05);
  const Lame lame = lameWithWidth(2e-2);
  for (std::uint8_t mask : kMasks) {
    for (int trial = 0; trial < 100; ++trial) {
      double a[6], b[6], mid[6];
      for (int e = 0; e < 6; ++e) {
        a[e] = strain(gen);
        b[e] = strain(gen);
        mid[e] = 0.5 * (a[e] + b[e]);
      }
      const double ea = strainState(lame, tet, a, mask, false).energy;
      const double eb = strainState(lame, tet, b, mask, false).energy;
      const double em = strainState(lame, tet, mid, mask, false).energy;
      EXPECT_LE(em, 0.5 * (ea + eb) + 1e-12 * std::max(1.0, ea + eb)) << int(mask);
    }
  }
  double eps[6];
  for (int e = 0; e < 6; ++e) eps[e] = -0.02 + 0.004 * e;
  for (std::uint8_t mask : kMasks) {
    const double hard = strainState(lameWithWidth(0.0), tet, eps, mask, false).energy;
    if (hard == 0.0) continue;
    double previousGap = INFINITY;
    for (double width : {1e-2, 1e-3, 1e-4, 1e-5}) {
      const double gap = hard - strainState(lameWithWidth(width), tet, eps, mask, false).energy;
      EXPECT_GE(gap, -1e-12 * hard);
      EXPECT_LT(gap, 0.3 * previousGap + 1e-12 * hard) << "mask " << int(mask) << " w " << width;
      previousGap = gap;
    }
    EXPECT_LT(previousGap, 5e-3 * hard) << "the gap is about 2 w / |eps| of the energy";
  }
}

}  // namespace
}  // namespace galsculpt

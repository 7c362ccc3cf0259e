// Hencky strains and von Mises flow in them (solver/fem/hencky_strain.h): the continued
// logarithm is the logarithm above its floor and twice differentiable across it; the deviatoric
// energy is the minimum over the flow (checked by a search over the flow), its slope the
// returned stress and its curvature the consistent tangent (central differences).
#include "solver/fem/hencky_strain.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace galsculpt::kernels {
namespace {

TEST(HenckyStrain, TheContinuedLogarithmIsTheLogarithmAboveItsFloorAndSmoothAcrossIt) {
  for (const double s : {0.1, 0.5, 1.0, 2.0}) {
    const ExtendedLog l = extendedLog(s);
    EXPECT_DOUBLE_EQ(l.value, std::log(s));
    EXPECT_DOUBLE_EQ(l.slope, 1.0 / s);
    EXPECT_DOUBLE_EQ(l.curvature, -1.0 / (s * s));
  }
  const double m = kLogStretchFloor, tiny = 1e-9;
  const ExtendedLog below = extendedLog(m - tiny), above = extendedLog(m + tiny);
  EXPECT_NEAR(below.value, above.value, 1e-7);
  EXPECT_NEAR(below.slope, above.slope, 1e-6);
  EXPECT_NEAR(below.curvature, above.curvature, 1e-4);
  // Below the floor, crushed and inverted (negative stretches): finite, increasing, its
  // derivatives those of its value.
  double last = -INFINITY;
  for (double s = -2.0; s < m; s += 0.01) {
    const ExtendedLog l = extendedLog(s);
    EXPECT_GT(l.value, last);
    EXPECT_GT(l.slope, 0.0);
    last = l.value;
    const double h = 1e-6;
    EXPECT_NEAR((extendedLog(s + h).value - extendedLog(s - h).value) / (2 * h), l.slope,
                1e-6 * l.slope);
    EXPECT_NEAR((extendedLog(s + h).slope - extendedLog(s - h).slope) / (2 * h), l.curvature,
                1e-5 * std::abs(l.curvature));
  }
}

// mu (s - sqrt(3/2) dg)^2 + yield dg + H/2 dg^2 at dg.
double flowObjective(double mu, double yield, double hardening, double s, double dg) {
  const double kept = s - std::sqrt(1.5) * dg;
  return mu * kept * kept + yield * dg + 0.5 * hardening * dg * dg;
}

TEST(HenckyStrain, TheDeviatoricEnergyIsTheLeastOverTheFlowAndItsDerivativesTheReturn) {
  const double mu = 7e4;
  for (const double hardening : {0.0, 1e4, 1e6}) {
    const double yield = 5e3;
    const double sYield = yield / (std::sqrt(6.0) * mu);
    for (const double s : {0.0, 0.5 * sYield, 0.999 * sYield, 1.001 * sYield, 3 * sYield, 0.8}) {
      SCOPED_TRACE(::testing::Message() << "H " << hardening << " s " << s);
      const DeviatoricFlow g = deviatoricFlow(mu, yield, hardening, s);
      // The least of the objective over a fine grid of flows never beats it.
      double least = INFINITY;
      for (int i = 0; i <= 20000; ++i)
        least = std::min(least, flowObjective(mu, yield, hardening, s, s * i / 10000.0));
      EXPECT_LE(g.energy, least + 1e-12 * std::max(1.0, least));
      EXPECT_NEAR(g.energy, flowObjective(mu, yield, hardening, s, g.plasticStrain),
                  1e-12 * std::max(1.0, g.energy));
      EXPECT_EQ(g.plasticStrain > 0.0, s > sYield);
      if (s > sYield) {
        // On the hardened surface: sqrt(6) mu s* = yield + H dg.
        EXPECT_NEAR(std::sqrt(6.0) * mu * g.keptFraction * s, yield + hardening * g.plasticStrain,
                    1e-9 * yield);
      }
      if (s > 0.0) {
        const double h = 1e-7 * std::max(s, sYield);
        const DeviatoricFlow plus = deviatoricFlow(mu, yield, hardening, s + h);
        const DeviatoricFlow minus = deviatoricFlow(mu, yield, hardening, s - h);
        const double slope = g.slopeOverS * s;
        EXPECT_NEAR((plus.energy - minus.energy) / (2 * h), slope, 1e-6 * (slope + mu * sYield));
        EXPECT_NEAR(slope, 2.0 * mu * g.keptFraction * s, 1e-9 * (slope + 1.0))
            << "the slope is the returned deviator's stress";
        if (std::abs(s - sYield) > 0.01 * sYield) {
          EXPECT_NEAR((plus.slopeOverS * (s + h) - minus.slopeOverS * (s - h)) / (2 * h),
                      g.curvature, 1e-5 * mu);
        }
      }
    }
  }
  // Without a yield stress it is elastic at every strain.
  const DeviatoricFlow elastic = deviatoricFlow(mu, 0.0, 1e4, 0.5);
  EXPECT_DOUBLE_EQ(elastic.energy, mu * 0.25);
  EXPECT_EQ(elastic.plasticStrain, 0.0);
}

// The return map's closed-form first test agrees with the SVD's strain on which side of the
// margin an elastic part lies (near-repeated stretches included), and leaves collapsed and
// inverted elements to the SVD.
TEST(HenckyStrain, TheClosedFormTestAgreesWithTheSvdsStrain) {
  const double mu = 7e4, yield = 1e3;
  std::mt19937 gen(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int inside = 0, outside = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const double size = std::pow(10.0, -4.0 + 3.0 * (trial % 1000) / 1000.0);
    M3 f = identity3();
    for (double& a : f.a) a += size * u(gen);
    if (trial % 7 == 0) {  // two stretches equal: a rotation of diag(a, a, b)
      const double a = 1.0 + size * u(gen), b = 1.0 + size * u(gen);
      M3 d{};
      d(0, 0) = d(1, 1) = a;
      d(2, 2) = b;
      M3 r, unused;
      double s[3];
      rotationVariantSvd(f, r, s, unused);
      f = multiply(r, d);
    }
    M3 uu, vv;
    double s[3];
    rotationVariantSvd(f, uu, s, vv);
    const double q = std::sqrt(6.0) * mu * henckyStrain(s).deviatorNorm;
    const bool clear = clearlyElastic(f, mu, yield, 0.9);
    if (q < 0.9 * yield * (1.0 - 1e-6)) {
      EXPECT_TRUE(clear) << trial;
      ++inside;
    } else if (q > 0.9 * yield * (1.0 + 1e-6)) {
      EXPECT_FALSE(clear) << trial;
      ++outside;
    }
  }
  EXPECT_GT(inside, 1000);
  EXPECT_GT(outside, 1000);
  M3 crushed = identity3();
  crushed(2, 2) = 0.05;
  EXPECT_FALSE(clearlyElastic(crushed, mu, 1e9, 0.9)) << "collapsed: the SVD decides";
  crushed(2, 2) = -0.5;
  EXPECT_FALSE(clearlyElastic(crushed, mu, 1e9, 0.9)) << "inverted: the SVD decides";
  EXPECT_TRUE(clearlyElastic(crushed, mu, 0.0, 0.9)) << "no yield stress: nothing flows";
}

TEST(HenckyStrain, TheStrainOfAVolumeChangeHasNoDeviator) {
  const double s[3] = {1.2, 1.2, 1.2};
  const HenckyStrain h = henckyStrain(s);
  EXPECT_NEAR(h.trace, 3.0 * std::log(1.2), 1e-15);
  EXPECT_NEAR(h.deviatorNorm, 0.0, 1e-15);
  const double t[3] = {2.0, 1.0, 0.5};
  const HenckyStrain g = henckyStrain(t);
  EXPECT_NEAR(g.trace, 0.0, 1e-15);
  EXPECT_NEAR(g.deviatorNorm, std::sqrt(2.0) * std::log(2.0), 1e-15);
}

}  // namespace
}  // namespace galsculpt::kernels

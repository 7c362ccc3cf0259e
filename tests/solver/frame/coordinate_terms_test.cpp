// The coordinate terms of the incremental potential (coordinate_terms.h): each term's gradient
// against central differences of its energy, its diagonal against differences of its gradient,
// and the list's sums in their order.
#include "solver/frame/coordinate_terms.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace galsculpt {
namespace {

constexpr int kVertices = 3;
constexpr double kDampingDiagonal[3 * kVertices] = {40, 55, 70, 35, 20, 90, 65, 45, 30};

// Inputs at y: βK₀ taken diagonal (kDampingDiagonal), so that dampedK = βK₀ (y - x_n) follows y
// and the damping's energy is separable per coordinate.
struct Fixture {
  std::vector<double> xhat, xn, mass, springK, springTarget, dampedK;
  Fixture() {
    for (int i = 0; i < 3 * kVertices; ++i) {
      xhat.push_back(0.1 * std::sin(1.3 * i));
      xn.push_back(0.05 * std::cos(0.7 * i));
      springTarget.push_back(0.2 * std::sin(0.4 * i + 1));
    }
    mass = {0.3, 0.5, 0.8};
    springK = {0.0, 120.0, 0.0};
  }
  CoordinateInputs at(const std::vector<double>& y) {
    dampedK.resize(y.size());
    for (size_t i = 0; i < y.size(); ++i) dampedK[i] = kDampingDiagonal[i] * (y[i] - xn[i]);
    return {xhat.data(),    xn.data(),  mass.data(), springK.data(),   springTarget.data(),
            dampedK.data(), 1.0 / 60.0, 0.4,         {0.0, -9.81, 0.0}};
  }
};

template <typename Term>
void expectDerivativesMatch(const char* name, bool damping) {
  Fixture f;
  std::vector<double> y(3 * kVertices);
  for (int i = 0; i < 3 * kVertices; ++i) y[i] = 0.07 * std::cos(2.1 * i + 0.3);
  const double step = 1e-6;
  for (int i = 0; i < 3 * kVertices; ++i) {
    auto energyAt = [&](double yi) {
      std::vector<double> z = y;
      z[i] = yi;
      return Term::energy(f.at(z), i, z.data());
    };
    auto gradientAt = [&](double yi) {
      std::vector<double> z = y;
      z[i] = yi;
      return Term::gradient(f.at(z), i, z.data());
    };
    const double fdGradient = (energyAt(y[i] + step) - energyAt(y[i] - step)) / (2 * step);
    const double g = gradientAt(y[i]);
    EXPECT_NEAR(g, fdGradient, 1e-6 * (1.0 + std::abs(g))) << name << " coordinate " << i;
    const CoordinateInputs c = f.at(y);
    // The diagonal: the mass's coefficient and the term's own entry (and, for damping, βK₀/h,
    // which the system's build adds from the frozen blocks).
    double diagonal = f.mass[i / 3] * Term::massCoefficient(c) + Term::diagonal(c, i / 3);
    if (damping) diagonal += kDampingDiagonal[i] / c.h;
    const double fdDiagonal = (gradientAt(y[i] + step) - gradientAt(y[i] - step)) / (2 * step);
    EXPECT_NEAR(diagonal, fdDiagonal, 1e-5 * (1.0 + std::abs(diagonal)))
        << name << " coordinate " << i;
  }
}

TEST(CoordinateTerms, EachTermsGradientAndDiagonalAreItsEnergysDerivatives) {
  expectDerivativesMatch<InertiaTerm>("inertia", false);
  expectDerivativesMatch<GravityTerm>("gravity", false);
  expectDerivativesMatch<DampingTerm>("damping", true);
  expectDerivativesMatch<SpringTerm>("spring", false);
}

// The list sums its terms in order, the pass terms' force after the first: the expression the
// frame's pinned bits were made with.
TEST(CoordinateTerms, TheListSumsItsTermsInOrder) {
  Fixture f;
  std::vector<double> y(3 * kVertices, 0.02);
  const CoordinateInputs c = f.at(y);
  for (int i = 0; i < 3 * kVertices; ++i) {
    const double m = f.mass[i / 3], dx = y[i] - f.xn[i], inertia = y[i] - f.xhat[i];
    const double k = f.springK[i / 3];
    double e = 0.5 / (c.h * c.h) * inertia * (m * inertia) - m * c.gravity[i % 3] * y[i] +
               0.5 / c.h * (c.alpha * dx * (m * dx) + dx * c.dampedK[i]);
    if (k > 0.0) e += 0.5 * k * (y[i] - f.springTarget[i]) * (y[i] - f.springTarget[i]);
    EXPECT_EQ(CoordinateTerms::energy(c, i, y.data()), e) << i;
    const double force = 0.3 * i - 1.0;
    double g = m * (y[i] - f.xhat[i]) / (c.h * c.h) + force - m * c.gravity[i % 3] +
               (c.alpha * (m * dx) + c.dampedK[i]) / c.h;
    if (k > 0.0) g += k * (y[i] - f.springTarget[i]);
    EXPECT_EQ(CoordinateTerms::gradient(c, i, y.data(), force), g) << i;
  }
  EXPECT_EQ(CoordinateTerms::massCoefficient(c), 1.0 / (c.h * c.h) + c.alpha / c.h);
  EXPECT_EQ(CoordinateTerms::diagonal(c, 1), 120.0);
  EXPECT_EQ(CoordinateTerms::diagonal(c, 0), 0.0);
}

}  // namespace
}  // namespace galsculpt

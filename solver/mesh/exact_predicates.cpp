#include "solver/mesh/exact_predicates.h"

#include <cmath>
#include <limits>
#include <vector>

namespace galsculpt {

namespace {

// A number represented exactly as the sum of its terms (not necessarily non-overlapping).
using Terms = std::vector<double>;

void twoSum(double a, double b, double& sum, double& error) {
  sum = a + b;
  const double bVirtual = sum - a;
  const double aVirtual = sum - bVirtual;
  error = (a - aVirtual) + (b - bVirtual);
}

Terms difference(double a, double b) {
  double s, e;
  twoSum(a, -b, s, e);
  return {s, e};
}

// Exact product: every pair of terms gives a product and its rounding error (fma is exact).
Terms product(const Terms& x, const Terms& y) {
  Terms out;
  out.reserve(2 * x.size() * y.size());
  for (double a : x) {
    for (double b : y) {
      const double p = a * b;
      out.push_back(p);
      out.push_back(std::fma(a, b, -p));
    }
  }
  return out;
}

Terms sum(Terms x, const Terms& y, double ySign) {
  for (double b : y) x.push_back(ySign * b);
  return x;
}

// Sign of the exact sum of the terms: grow a non-overlapping expansion term by term (each step
// exact), then its largest-magnitude non-zero component carries the sign of the whole.
int signOfSum(const Terms& terms) {
  std::vector<double> expansion;
  expansion.reserve(terms.size() + 1);
  for (double t : terms) {
    double q = t;
    std::vector<double> grown;
    grown.reserve(expansion.size() + 1);
    for (double e : expansion) {
      double s, err;
      twoSum(q, e, s, err);
      if (err != 0.0) grown.push_back(err);
      q = s;
    }
    if (q != 0.0) grown.push_back(q);
    expansion.swap(grown);
  }
  if (expansion.empty()) return 0;
  return expansion.back() > 0.0 ? 1 : -1;
}

}  // namespace

int orient3dExact(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Terms adx = difference(a.x(), d.x()), ady = difference(a.y(), d.y()),
              adz = difference(a.z(), d.z());
  const Terms bdx = difference(b.x(), d.x()), bdy = difference(b.y(), d.y()),
              bdz = difference(b.z(), d.z());
  const Terms cdx = difference(c.x(), d.x()), cdy = difference(c.y(), d.y()),
              cdz = difference(c.z(), d.z());
  const Terms minorA = sum(product(bdy, cdz), product(bdz, cdy), -1.0);
  const Terms minorB = sum(product(bdz, cdx), product(bdx, cdz), -1.0);
  const Terms minorC = sum(product(bdx, cdy), product(bdy, cdx), -1.0);
  Terms det = product(adx, minorA);
  det = sum(det, product(ady, minorB), 1.0);
  det = sum(det, product(adz, minorC), 1.0);
  return signOfSum(det);
}

int orient3d(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3 ad = a - d, bd = b - d, cd = c - d;
  const double m1 = bd.y() * cd.z(), m2 = bd.z() * cd.y();
  const double m3 = bd.z() * cd.x(), m4 = bd.x() * cd.z();
  const double m5 = bd.x() * cd.y(), m6 = bd.y() * cd.x();
  const double det = ad.x() * (m1 - m2) + ad.y() * (m3 - m4) + ad.z() * (m5 - m6);
  const double permanent = std::abs(ad.x()) * (std::abs(m1) + std::abs(m2)) +
                           std::abs(ad.y()) * (std::abs(m3) + std::abs(m4)) +
                           std::abs(ad.z()) * (std::abs(m5) + std::abs(m6));
  // Shewchuk's bound for this evaluation order, (7 + 56 eps) eps, eps = 2^-53.
  constexpr double eps = std::numeric_limits<double>::epsilon() / 2.0;
  constexpr double bound = (7.0 + 56.0 * eps) * eps;
  if (det > bound * permanent) return 1;
  if (-det > bound * permanent) return -1;
  return orient3dExact(a, b, c, d);
}

}  // namespace galsculpt

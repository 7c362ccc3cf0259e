#include "tet_element.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace galsculpt {

namespace {

// F = U diag(s) V^T with U, V rotations; an inversion shows as s[2] < 0.
struct RotationSvd {
  Eigen::Matrix3d u, v;
  Eigen::Vector3d s;
};

// Fast path: eigenvectors of F^T F in closed form give V and the singular values; U follows
// from F V. Used only where it is well conditioned (checked); otherwise Jacobi SVD below.
bool svdFromNormalMatrix(const Eigen::Matrix3d& f, RotationSvd& r) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
  es.computeDirect(f.transpose() * f);
  const Eigen::Vector3d lambda = es.eigenvalues();  // ascending
  if (!(lambda[2] > 0.0) || !(lambda[1] > 1e-8 * lambda[2])) return false;
  Eigen::Matrix3d v;
  v << es.eigenvectors().col(2), es.eigenvectors().col(1), es.eigenvectors().col(0);
  if (!((v.transpose() * v - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() < 1e-10))
    return false;
  if (v.determinant() < 0.0) v.col(2) *= -1.0;
  const double s0 = std::sqrt(lambda[2]), s1 = std::sqrt(lambda[1]);
  const Eigen::Vector3d u0 = f * v.col(0) / s0, u1 = f * v.col(1) / s1;
  if (!(std::abs(u0.dot(u1)) < 1e-9 && std::abs(u0.squaredNorm() - 1.0) < 1e-9 &&
        std::abs(u1.squaredNorm() - 1.0) < 1e-9)) {
    return false;
  }
  r.u.col(0) = u0;
  r.u.col(1) = u1;
  r.u.col(2) = u0.cross(u1);
  r.v = v;
  r.s = Eigen::Vector3d(s0, s1, r.u.col(2).dot(f * v.col(2)));  // signed: negative when inverted
  const double scale = std::max(f.cwiseAbs().maxCoeff(), 1e-300);
  return (r.u * r.s.asDiagonal() * r.v.transpose() - f).cwiseAbs().maxCoeff() < 1e-11 * scale;
}

RotationSvd rotationVariantSvd(const Eigen::Matrix3d& f) {
  RotationSvd fast;
  if (svdFromNormalMatrix(f, fast)) return fast;
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(f, Eigen::ComputeFullU | Eigen::ComputeFullV);
  RotationSvd r{svd.matrixU(), svd.matrixV(), svd.singularValues()};
  if (r.u.determinant() < 0.0) {
    r.u.col(2) *= -1.0;
    r.s[2] *= -1.0;
  }
  if (r.v.determinant() < 0.0) {
    r.v.col(2) *= -1.0;
    r.s[2] *= -1.0;
  }
  return r;
}

Eigen::Matrix<double, 9, 1> vecOf(const Eigen::Matrix3d& m) {
  return Eigen::Map<const Eigen::Matrix<double, 9, 1>>(m.data());
}

// Quotient (a / b) with b kept away from zero, and its limit where numerator and denominator
// vanish together (equal singular values).
double safeQuotient(double numerator, double denominator, double limit) {
  const double eps = 1e-8;
  if (std::abs(denominator) < eps) return limit;
  return numerator / denominator;
}

Mat9 eigenSystemHessian(const RotationSvd& svd, const SingularValueEnergy& e, bool projectSpd) {
  Mat9 h = Mat9::Zero();
  auto add = [&](double lambda, const Eigen::Matrix3d& mode) {
    if (projectSpd) lambda = std::max(lambda, 0.0);
    if (lambda == 0.0) return;
    const Eigen::Matrix<double, 9, 1> q = vecOf(mode);
    h.noalias() += lambda * q * q.transpose();
  };
  // Scaling modes: the 3x3 Hessian in singular values.
  // Closed-form 3x3 eigen-solve, with the iterative solver as the fallback where the closed form
  // loses orthogonality (nearly repeated eigenvalues).
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> scaling;
  scaling.computeDirect(e.hessian);
  const Eigen::Matrix3d& q = scaling.eigenvectors();
  const double scale = std::max(e.hessian.cwiseAbs().maxCoeff(), 1e-300);
  if (!((q.transpose() * q - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() < 1e-10) ||
      !((q * scaling.eigenvalues().asDiagonal() * q.transpose() - e.hessian).cwiseAbs().maxCoeff() <
        1e-11 * scale)) {
    scaling.compute(e.hessian);
  }
  for (int m = 0; m < 3; ++m) {
    add(scaling.eigenvalues()[m],
        svd.u * scaling.eigenvectors().col(m).asDiagonal() * svd.v.transpose());
  }
  // Twist and flip modes of each pair of singular values.
  const double invSqrt2 = 1.0 / std::sqrt(2.0);
  for (int i = 0; i < 3; ++i) {
    for (int j = i + 1; j < 3; ++j) {
      Eigen::Matrix3d twist = Eigen::Matrix3d::Zero(), flip = Eigen::Matrix3d::Zero();
      twist(i, j) = invSqrt2;
      twist(j, i) = -invSqrt2;
      flip(i, j) = invSqrt2;
      flip(j, i) = invSqrt2;
      const double gi = e.gradient[i], gj = e.gradient[j], si = svd.s[i], sj = svd.s[j];
      const double twistValue = safeQuotient(gi + gj, si + sj, e.hessian(i, i) + e.hessian(i, j));
      const double flipValue = safeQuotient(gi - gj, si - sj, e.hessian(i, i) - e.hessian(i, j));
      add(twistValue, svd.u * twist * svd.v.transpose());
      add(flipValue, svd.u * flip * svd.v.transpose());
    }
  }
  return h;
}

Eigen::Matrix3d symmetricMatrix(const Eigen::Matrix<double, 6, 1>& v) {
  Eigen::Matrix3d e;
  e << v[0], v[3], v[4], v[3], v[1], v[5], v[4], v[5], v[2];
  return e;
}

}  // namespace

void evaluateEdgeStrainElement(const Lame& lame, const TetRest& rest, const TetPoints& x,
                               const EdgeDamage& damage, HessianMode mode, ElementEval& out) {
  // Isotropic elasticity on (E11,E22,E33,E12,E13,E23); shear entries count twice in E:E.
  Eigen::Matrix<double, 6, 6> c = Eigen::Matrix<double, 6, 6>::Zero();
  c.topLeftCorner<3, 3>().setConstant(lame.lambda);
  for (int i = 0; i < 3; ++i) c(i, i) += 2.0 * lame.mu;
  for (int i = 3; i < 6; ++i) c(i, i) = 4.0 * lame.mu;
  Eigen::Matrix<double, 6, 6> k = rest.strainFromEdges.transpose() * c * rest.strainFromEdges;
  // When only two opposite edges are intact, the element's vertices form two pieces, one per
  // edge (every other damage pattern leaves the four vertices connected). Their strains must
  // not be coupled, or one piece's stretch would push the other: adding the PSD term
  // |k01| (u0 - sign(k01) u1)(u0 - sign(k01) u1)^T removes k01 and keeps K PSD for any set of
  // compressed damaged edges that stay active.
  for (const auto& [e0, e1] : {std::pair{0, 5}, std::pair{1, 4}, std::pair{2, 3}}) {
    if (damage.intact != ((1u << e0) | (1u << e1))) continue;
    const double k01 = k(e0, e1);
    const double sign = k01 >= 0.0 ? 1.0 : -1.0;
    k(e0, e0) += std::abs(k01);
    k(e1, e1) += std::abs(k01);
    k(e0, e1) -= sign * std::abs(k01);
    k(e1, e0) -= sign * std::abs(k01);
  }

  Eigen::Matrix<double, 6, 1> strain, slope;  // masked strain and d(masked)/d(raw)
  std::array<Eigen::Vector3d, 6> d;
  for (int e = 0; e < 6; ++e) {
    d[e] = x[kTetEdges[e][1]] - x[kTetEdges[e][0]];
    const double raw = (d[e].squaredNorm() - rest.restLengthSq[e]) / (2.0 * rest.restLengthSq[e]);
    const bool intact = (damage.intact >> e) & 1;
    const bool pushes = !intact && damage.compressionResists && raw < 0.0;
    slope[e] = (intact || pushes) ? 1.0 : 0.0;
    strain[e] = slope[e] * raw;
  }
  const Eigen::Matrix<double, 6, 1> tension = k * strain;  // dPsi/d(masked strain)
  out.energy = rest.volume * 0.5 * strain.dot(tension);
  out.gradient.setZero();
  // d eps_k / d x_b = d_k / |D_k|^2 = -d eps_k / d x_a for edge (a, b).
  Eigen::Matrix<double, 6, 12> g = Eigen::Matrix<double, 6, 12>::Zero();
  for (int e = 0; e < 6; ++e) {
    const Eigen::Vector3d grad = slope[e] * d[e] / rest.restLengthSq[e];
    g.block<1, 3>(e, 3 * kTetEdges[e][1]) = grad.transpose();
    g.block<1, 3>(e, 3 * kTetEdges[e][0]) = -grad.transpose();
  }
  out.gradient = rest.volume * g.transpose() * tension;
  if (mode == HessianMode::None) return;
  out.hessian = rest.volume * g.transpose() * k * g;  // PSD: K is PSD
  for (int e = 0; e < 6; ++e) {
    // The second derivative of eps_k is [I -I; -I I] / |D_k|^2, PSD: only a compressive edge
    // force makes it indefinite, so projection drops those terms.
    double t = slope[e] * tension[e] / rest.restLengthSq[e];
    if (mode == HessianMode::ProjectedSpd) t = std::max(t, 0.0);
    const int a = 3 * kTetEdges[e][0], b = 3 * kTetEdges[e][1];
    const Eigen::Matrix3d block = rest.volume * t * Eigen::Matrix3d::Identity();
    out.hessian.block<3, 3>(a, a) += block;
    out.hessian.block<3, 3>(b, b) += block;
    out.hessian.block<3, 3>(a, b) -= block;
    out.hessian.block<3, 3>(b, a) -= block;
  }
}

namespace {

Eigen::Matrix3d damagedGreenStrain(const TetRest& rest, const TetPoints& x,
                                   const EdgeDamage& damage) {
  Eigen::Matrix<double, 6, 1> strain;
  for (int e = 0; e < 6; ++e) {
    const Eigen::Vector3d d = x[kTetEdges[e][1]] - x[kTetEdges[e][0]];
    const double raw = (d.squaredNorm() - rest.restLengthSq[e]) / (2.0 * rest.restLengthSq[e]);
    const bool intact = (damage.intact >> e) & 1;
    strain[e] = (intact || (damage.compressionResists && raw < 0.0)) ? raw : 0.0;
  }
  return symmetricMatrix(rest.strainFromEdges * strain);
}

// Row a: d vec(F) / d x_a in compact form, F = sum_a x_a c_a^T.
Eigen::Matrix<double, 4, 3> shapeGradients(const TetRest& rest) {
  Eigen::Matrix<double, 4, 3> c;
  c.bottomRows<3>() = rest.dmInverse;
  c.row(0) = -rest.dmInverse.colwise().sum();
  return c;
}

// Psi and P straight from F for StVK and stable neo-Hookean (the same functions as their
// singular-value forms; the finite-difference tests compare the two paths).
Eigen::Matrix3d directStress(MaterialModel model, const Lame& lame, const Eigen::Matrix3d& f,
                             double& psi) {
  if (model == MaterialModel::StVK) {
    const Eigen::Matrix3d e = 0.5 * (f.transpose() * f - Eigen::Matrix3d::Identity());
    const double trace = e.trace();
    psi = lame.mu * e.squaredNorm() + 0.5 * lame.lambda * trace * trace;
    return f * (2.0 * lame.mu * e + lame.lambda * trace * Eigen::Matrix3d::Identity());
  }
  const double muS = 4.0 / 3.0 * lame.mu;
  const double lambdaS = lame.lambda + 5.0 / 6.0 * lame.mu;
  const double alpha = 1.0 + 0.75 * muS / lambdaS;
  const double ic = f.squaredNorm();
  const double j = f.determinant();
  Eigen::Matrix3d cofactor;  // dJ/dF
  cofactor.col(0) = f.col(1).cross(f.col(2));
  cofactor.col(1) = f.col(2).cross(f.col(0));
  cofactor.col(2) = f.col(0).cross(f.col(1));
  const double restEnergy =
      0.5 * lambdaS * (1.0 - alpha) * (1.0 - alpha) - 0.5 * muS * std::log(4.0);
  psi = 0.5 * muS * (ic - 3.0) + 0.5 * lambdaS * (j - alpha) * (j - alpha) -
        0.5 * muS * std::log(ic + 1.0) - restEnergy;
  return muS * (1.0 - 1.0 / (ic + 1.0)) * f + lambdaS * (j - alpha) * cofactor;
}

}  // namespace

TetRest computeTetRest(const TetPoints& p) {
  TetRest r;
  Eigen::Matrix3d dm;
  dm << p[1] - p[0], p[2] - p[0], p[3] - p[0];
  const double det = dm.determinant();
  if (!(std::abs(det) > 0.0)) throw std::invalid_argument("degenerate rest tet");
  r.dmInverse = dm.inverse();
  r.volume = std::abs(det) / 6.0;
  Eigen::Matrix<double, 6, 6> b;
  for (int e = 0; e < 6; ++e) {
    const Eigen::Vector3d d = p[kTetEdges[e][1]] - p[kTetEdges[e][0]];
    r.restLengthSq[e] = d.squaredNorm();
    const Eigen::Vector3d n = d / d.norm();
    b.row(e) << n.x() * n.x(), n.y() * n.y(), n.z() * n.z(), 2 * n.x() * n.y(), 2 * n.x() * n.z(),
        2 * n.y() * n.z();
  }
  r.strainFromEdges = b.inverse();
  return r;
}

Eigen::Matrix3d deformationGradient(const TetRest& rest, const TetPoints& x) {
  Eigen::Matrix3d ds;
  ds << x[1] - x[0], x[2] - x[0], x[3] - x[0];
  return ds * rest.dmInverse;
}

Eigen::Matrix3d firstPiolaStress(MaterialModel model, const Lame& lame, const Eigen::Matrix3d& f) {
  const RotationSvd svd = rotationVariantSvd(f);
  const SingularValueEnergy e = evaluateSingularValueEnergy(model, lame, svd.s);
  return svd.u * e.gradient.asDiagonal() * svd.v.transpose();
}

Mat9 stressDerivative(MaterialModel model, const Lame& lame, const Eigen::Matrix3d& f,
                      bool projectSpd) {
  const RotationSvd svd = rotationVariantSvd(f);
  return eigenSystemHessian(svd, evaluateSingularValueEnergy(model, lame, svd.s), projectSpd);
}

void evaluateElement(MaterialModel model, const Lame& lame, const TetRest& rest, const TetPoints& x,
                     const EdgeDamage& damage, HessianMode mode, ElementEval& out) {
  if (damage.intact != kAllEdgesIntact) {
    evaluateEdgeStrainElement(lame, rest, x, damage, mode, out);
    return;
  }
  const Eigen::Matrix3d f = deformationGradient(rest, x);
  const Eigen::Matrix<double, 4, 3> c = shapeGradients(rest);
  if (mode == HessianMode::None && model != MaterialModel::Corotational) {
    // Energy and force without an SVD: both models are polynomial in F (and J) directly.
    double psi = 0.0;
    const Eigen::Matrix3d p = directStress(model, lame, f, psi);
    out.energy = rest.volume * psi;
    for (int a = 0; a < 4; ++a)
      out.gradient.segment<3>(3 * a) = rest.volume * (p * c.row(a).transpose());
    return;
  }
  const RotationSvd svd = rotationVariantSvd(f);
  const SingularValueEnergy e = evaluateSingularValueEnergy(model, lame, svd.s);
  const Eigen::Matrix3d p = svd.u * e.gradient.asDiagonal() * svd.v.transpose();
  out.energy = rest.volume * e.energy;
  // dF/dx has the structure dF_ij/dx_ak = delta_ik c_aj (c_a the rows of the shape-function
  // gradients); using it directly is several times cheaper than the dense 9x12 products.
  for (int a = 0; a < 4; ++a)
    out.gradient.segment<3>(3 * a) = rest.volume * (p * c.row(a).transpose());
  if (mode == HessianMode::None) return;
  const Mat9 dpdf = eigenSystemHessian(svd, e, mode == HessianMode::ProjectedSpd);
  // K_ab = V sum_{j,n} c_aj c_bn H_(j,n), H_(j,n) the 3x3 block of dP/dF at columns j, n of F.
  std::array<Eigen::Matrix3d, 12> w;  // w[3b + j] = sum_n c_bn H_(j,n)
  for (int b = 0; b < 4; ++b) {
    for (int j = 0; j < 3; ++j) {
      w[3 * b + j] = c(b, 0) * dpdf.block<3, 3>(3 * j, 0) + c(b, 1) * dpdf.block<3, 3>(3 * j, 3) +
                     c(b, 2) * dpdf.block<3, 3>(3 * j, 6);
    }
  }
  for (int a = 0; a < 4; ++a) {
    for (int b = 0; b < 4; ++b) {
      out.hessian.block<3, 3>(3 * a, 3 * b) =
          rest.volume * (c(a, 0) * w[3 * b] + c(a, 1) * w[3 * b + 1] + c(a, 2) * w[3 * b + 2]);
    }
  }
}

std::array<double, 6> edgeNormalStress(MaterialModel model, const Lame& lame, const TetRest& rest,
                                       const TetPoints& x, const EdgeDamage& damage) {
  const Eigen::Matrix3d f = deformationGradient(rest, x);
  Eigen::Matrix3d p;
  if (damage.intact == kAllEdgesIntact) {
    p = firstPiolaStress(model, lame, f);
  } else {
    const Eigen::Matrix3d e = damagedGreenStrain(rest, x, damage);
    p = f * (2.0 * lame.mu * e + lame.lambda * e.trace() * Eigen::Matrix3d::Identity());
  }
  const double j = f.determinant();
  // Cauchy stress; a collapsed or inverted element keeps the Piola-Kirchhoff scale instead of
  // dividing by a vanishing or negative volume ratio.
  const Eigen::Matrix3d sigma = p * f.transpose() / (j > 1e-6 ? j : 1.0);
  std::array<double, 6> out{};
  for (int e = 0; e < 6; ++e) {
    const Eigen::Vector3d d = x[kTetEdges[e][1]] - x[kTetEdges[e][0]];
    const double len = d.norm();
    const Eigen::Vector3d n = len > 0.0 ? Eigen::Vector3d(d / len) : Eigen::Vector3d::Zero();
    out[e] = n.dot(sigma * n);
  }
  return out;
}

}  // namespace galsculpt

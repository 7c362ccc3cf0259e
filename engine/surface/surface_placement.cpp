// Where the surface builder's points lie (surface_builder.h): each point's support corners and
// weights, prepared when the topology changes, and the positions evaluated every frame.
#include <algorithm>
#include <cmath>

#include "engine/surface/surface_builder.h"
#include "engine/surface/surface_point_keys.h"

namespace galsculpt {

using namespace surface_keys;

int SurfaceBuilder::supportOf(const SimModel& model, std::uint64_t key, int (&support)[4]) const {
  const int index = keyIndex(key);
  int n = 0;
  switch (keyKind(key)) {
    case kEdgePoint:
      support[n++] = model.edges[index][0];
      support[n++] = model.edges[index][1];
      break;
    case kFacePoint:
      for (int v : faceCorners_[index]) support[n++] = v;
      break;
    case kTetPoint:
      for (int v : model.mesh.tets[index]) support[n++] = v;
      break;
  }
  return n;
}

void SurfaceBuilder::preparePlacements(const SimModel& model) {
  // What each surface vertex's position is made of, in output order, so that the per-frame pass
  // reads it sequentially; and the corners of copies that hold only part of their point's
  // support, which need F_v.
  deformedVertices_.clear();
  std::vector<char> seen(model.numVertices(), 0);
  placements_.resize(outSource_.size());
  for (size_t i = 0; i < outSource_.size(); ++i) {
    const std::int64_t source = outSource_[i];
    Placement& p = placements_[i];
    if (source < 0) {
      p.count = 0;
      p.support[0] = static_cast<int>(-source - 1);
      continue;
    }
    const std::uint64_t key = pointKey_[source];
    int support[4];
    p.count = supportOf(model, key, support);
    std::copy(support, support + p.count, p.support.begin());
    p.mask = keyMask(key);
    p.rest = pointRest_[source];
    if (p.mask == (1u << p.count) - 1) continue;
    for (int k = 0; k < p.count; ++k) {
      if ((p.mask & (1u << k)) && !seen[support[k]]) {
        seen[support[k]] = 1;
        deformedVertices_.push_back(support[k]);
      }
    }
  }
}

Eigen::Matrix3d SurfaceBuilder::fitDeformation(const SimModel& model, const SimState& state,
                                               int v) const {
  // Least-squares fit of dx = F dX over the undamaged edges at v: the deformation of v's own
  // side. Too few directions (a vertex on a thin sliver): regularized towards the rotation that
  // best carries its edges where they are (Kabsch), not towards the identity, which turns a
  // sliver that has tumbled over inside out (a single edge reversed gave F a negative stretch).
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero(), B = Eigen::Matrix3d::Zero();
  for (int k = vertexEdgeStart_[v]; k < vertexEdgeStart_[v + 1]; ++k) {
    const int e = vertexEdges_[k];
    if (state.damaged[e]) continue;
    const int u = model.edges[e][0] == v ? model.edges[e][1] : model.edges[e][0];
    const Vec3 dX = model.mesh.vertices[u] - model.mesh.vertices[v];
    const Vec3 dx = state.x[u] - state.x[v];
    A += dX * dX.transpose();
    B += dx * dX.transpose();
  }
  const double scale = A.trace() / 3.0;
  if (scale <= 0.0) return Eigen::Matrix3d::Identity();
  // A direction the edges barely reach is not fitted: a residual of the neighbours' motion off
  // the affine (a tearing zone strains its edges unevenly) divided by a small eigenvalue of A
  // blew F up 20-fold at a crack-face vertex whose edges were nearly coplanar, and the surface
  // around it shot out as a spike across the opened crack (measured on a torn steak).
  constexpr double kConstrained = 0.02;  // of the mean eigenvalue
  // Most vertices: det A = l0 l1 l2 with l1 l2 <= (1.5 scale)^2 bounds the smallest eigenvalue
  // l0 from below without solving for it (every frame, for every vertex beside a crack).
  if (A.determinant() >= kConstrained * 2.25 * scale * scale * scale) return B * A.inverse();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
  eigen.computeDirect(A);
  const Vec3 lambda = eigen.eigenvalues();  // ascending
  if (lambda(0) >= kConstrained * scale) return B * A.inverse();
  // The rotation is left free about directions no edge constrains; the small identity term
  // picks the one nearest the identity there (at rest: the identity).
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(B + 1e-6 * scale * Eigen::Matrix3d::Identity(),
                                              Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d flip = Eigen::Matrix3d::Identity();
  flip(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0.0 ? -1.0 : 1.0;
  const Eigen::Matrix3d rotation = svd.matrixU() * flip * svd.matrixV().transpose();
  // F = R + G with G the least-squares correction (G dX = dx - R dX) in the directions the
  // edges constrain (A's pseudo-inverse over them), the rotation alone in the others.
  Eigen::Matrix3d constrained = Eigen::Matrix3d::Zero();
  for (int k = 0; k < 3; ++k)
    if (lambda(k) >= kConstrained * scale)
      constrained +=
          eigen.eigenvectors().col(k) * eigen.eigenvectors().col(k).transpose() / lambda(k);
  return rotation + (B - rotation * A) * constrained;
}

void SurfaceBuilder::evaluatePositions(const SimModel& model, const SimState& state) {
  // Serial: the pass is memory-bound (two threads gained 25 % on the 1.8M-face surface).
  for (int v : deformedVertices_) deformation_[v] = fitDeformation(model, state, v);
  std::vector<Vec3>& out = surface_.mesh.vertices;
  out.resize(outSource_.size());
  const std::vector<Vec3>& X = model.mesh.vertices;
  const size_t count = placements_.size();
  for (size_t i = 0; i < count; ++i) {
    const Placement& p = placements_[i];
    if (p.count == 0) {
      out[i] = state.x[p.support[0]];
      continue;
    }
    if (p.mask == (1u << p.count) - 1) {
      Vec3 sum = Vec3::Zero();
      for (int k = 0; k < p.count; ++k) sum += state.x[p.support[k]];
      out[i] = sum / p.count;
      continue;
    }
    Vec3 sum = Vec3::Zero();
    int held = 0;
    for (int k = 0; k < p.count; ++k) {
      if (!(p.mask & (1u << k))) continue;
      const int v = p.support[k];
      sum += state.x[v] + deformation_[v] * (p.rest - X[v]);
      ++held;
    }
    out[i] = sum / held;
  }
}

}  // namespace galsculpt

#include "engine/surface/surface_bvh.h"

#include <algorithm>
#include <cmath>

namespace galsculpt {

namespace {

// Möller-Trumbore, both sides; t of the hit or a negative value.
double rayTriangle(const Vec3& o, const Vec3& d, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 e1 = b - a, e2 = c - a;
  const Vec3 p = d.cross(e2);
  const double det = e1.dot(p);
  if (std::abs(det) < 1e-300) return -1.0;
  const double inv = 1.0 / det;
  const Vec3 s = o - a;
  const double u = s.dot(p) * inv;
  if (u < 0.0 || u > 1.0) return -1.0;
  const Vec3 q = s.cross(e1);
  const double v = d.dot(q) * inv;
  if (v < 0.0 || u + v > 1.0) return -1.0;
  return e2.dot(q) * inv;
}

bool rayBox(const Vec3& o, const Vec3& invD, const Vec3& lo, const Vec3& hi, double maxT) {
  double t0 = 0.0, t1 = maxT;
  for (int k = 0; k < 3; ++k) {
    double a = (lo[k] - o[k]) * invD[k], b = (hi[k] - o[k]) * invD[k];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
    if (t0 > t1) return false;
  }
  return true;
}

}  // namespace

int SurfaceBvh::buildNode(const TriMesh& mesh, std::vector<Vec3>& centroids, int first, int count) {
  const int id = static_cast<int>(nodes_.size());
  nodes_.push_back({});
  Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
  Vec3 clo = lo, chi = hi;
  for (int i = first; i < first + count; ++i) {
    for (int c : mesh.faces[faces_[i]]) {
      lo = lo.cwiseMin(mesh.vertices[c]);
      hi = hi.cwiseMax(mesh.vertices[c]);
    }
    clo = clo.cwiseMin(centroids[faces_[i]]);
    chi = chi.cwiseMax(centroids[faces_[i]]);
  }
  nodes_[id].min = lo;
  nodes_[id].max = hi;
  if (count <= 4) {
    nodes_[id].first = first;
    nodes_[id].count = count;
    return id;
  }
  int axis = 0;
  (chi - clo).maxCoeff(&axis);
  const int half = count / 2;
  std::nth_element(faces_.begin() + first, faces_.begin() + first + half,
                   faces_.begin() + first + count,
                   [&](int a, int b) { return centroids[a][axis] < centroids[b][axis]; });
  const int left = buildNode(mesh, centroids, first, half);
  const int right = buildNode(mesh, centroids, first + half, count - half);
  nodes_[id].left = left;
  nodes_[id].right = right;
  return id;
}

void SurfaceBvh::build(const TriMesh& mesh) {
  nodes_.clear();
  faces_.resize(mesh.faces.size());
  for (size_t f = 0; f < faces_.size(); ++f) faces_[f] = static_cast<int>(f);
  if (faces_.empty()) return;
  std::vector<Vec3> centroids(mesh.faces.size());
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    const Tri& t = mesh.faces[f];
    centroids[f] = (mesh.vertices[t[0]] + mesh.vertices[t[1]] + mesh.vertices[t[2]]) / 3.0;
  }
  nodes_.reserve(2 * faces_.size() / 4 + 2);
  buildNode(mesh, centroids, 0, static_cast<int>(faces_.size()));
}

void SurfaceBvh::refit(const TriMesh& mesh) {
  // Children always follow their parent in nodes_, so a reverse sweep is bottom-up.
  for (int i = static_cast<int>(nodes_.size()) - 1; i >= 0; --i) {
    Node& n = nodes_[i];
    if (n.left < 0) {
      n.min = Vec3::Constant(1e300);
      n.max = Vec3::Constant(-1e300);
      for (int k = n.first; k < n.first + n.count; ++k) {
        for (int c : mesh.faces[faces_[k]]) {
          n.min = n.min.cwiseMin(mesh.vertices[c]);
          n.max = n.max.cwiseMax(mesh.vertices[c]);
        }
      }
    } else {
      n.min = nodes_[n.left].min.cwiseMin(nodes_[n.right].min);
      n.max = nodes_[n.left].max.cwiseMax(nodes_[n.right].max);
    }
  }
}

std::optional<RayHit> SurfaceBvh::intersect(const TriMesh& mesh, const Vec3& origin,
                                            const Vec3& direction, double maxT) const {
  if (nodes_.empty()) return std::nullopt;
  const Vec3 d = direction.normalized();
  const Vec3 invD(1.0 / d.x(), 1.0 / d.y(), 1.0 / d.z());
  RayHit best;
  double bestT = maxT;
  int stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[stack[--top]];
    if (!rayBox(origin, invD, n.min, n.max, bestT)) continue;
    if (n.left >= 0) {
      stack[top++] = n.left;
      stack[top++] = n.right;
      continue;
    }
    for (int k = n.first; k < n.first + n.count; ++k) {
      const Tri& t = mesh.faces[faces_[k]];
      const double hit =
          rayTriangle(origin, d, mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]);
      if (hit > 0.0 && hit <= bestT) {
        bestT = hit;
        best.face = faces_[k];
      }
    }
  }
  if (best.face < 0) return std::nullopt;
  const Tri& t = mesh.faces[best.face];
  best.distance = bestT;
  best.point = origin + bestT * d;
  const Vec3 n =
      (mesh.vertices[t[1]] - mesh.vertices[t[0]]).cross(mesh.vertices[t[2]] - mesh.vertices[t[0]]);
  best.normal = n.norm() > 0.0 ? Vec3(n.normalized()) : Vec3::Zero();
  return best;
}

namespace {

// The point of triangle abc nearest to p (Ericson, Real-Time Collision Detection, 5.1.5).
Vec3 closestOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return a;
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return a + d1 / (d1 - d3) * ab;
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
    return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  const double denom = va + vb + vc;
  if (!(std::abs(denom) > 0.0)) return a;  // a degenerate triangle: its corner will do
  return a + (vb / denom) * ab + (vc / denom) * ac;
}

double boxDistanceSquared(const Vec3& p, const Vec3& min, const Vec3& max) {
  return (min - p).cwiseMax(p - max).cwiseMax(0.0).squaredNorm();
}

}  // namespace

double SurfaceBvh::distance(const TriMesh& mesh, const Vec3& p) const {
  if (nodes_.empty()) return 0.0;
  double best = 1e300;  // squared
  int stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[stack[--top]];
    if (boxDistanceSquared(p, n.min, n.max) >= best) continue;
    if (n.left >= 0) {
      // The nearer child last, so that it is searched first.
      const Node& l = nodes_[n.left];
      const Node& r = nodes_[n.right];
      const bool leftNearer =
          boxDistanceSquared(p, l.min, l.max) < boxDistanceSquared(p, r.min, r.max);
      stack[top++] = leftNearer ? n.right : n.left;
      stack[top++] = leftNearer ? n.left : n.right;
      continue;
    }
    for (int k = n.first; k < n.first + n.count; ++k) {
      const Tri& t = mesh.faces[faces_[k]];
      const Vec3 q =
          closestOnTriangle(p, mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]);
      best = std::min(best, (q - p).squaredNorm());
    }
  }
  return std::sqrt(best);
}

std::optional<RayHit> SurfacePicker::intersect(const TriMesh& mesh, std::uint64_t topology,
                                               std::uint64_t generation, const Vec3& origin,
                                               const Vec3& direction) {
  if (topology != topology_ || mesh.numFaces() != faces_) {
    bvh_.build(mesh);
  } else if (generation != generation_) {
    bvh_.refit(mesh);
  }
  topology_ = topology;
  faces_ = mesh.numFaces();
  generation_ = generation;
  return bvh_.intersect(mesh, origin, direction);
}

}  // namespace galsculpt

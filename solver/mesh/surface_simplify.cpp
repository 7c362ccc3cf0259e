#include "solver/mesh/surface_simplify.h"

#include <algorithm>
#include <cmath>
#include <queue>

namespace galsculpt {

namespace {

// Symmetric 4x4 quadric of squared distances to a set of planes.
using Quadric = Eigen::Matrix4d;

Quadric planeQuadric(const Vec3& a, const Vec3& b, const Vec3& c) {
  Vec3 n = (b - a).cross(c - a);
  const double twiceArea = n.norm();
  if (twiceArea <= 0.0) return Quadric::Zero();
  n /= twiceArea;
  const Eigen::Vector4d p(n.x(), n.y(), n.z(), -n.dot(a));
  return 0.5 * twiceArea * (p * p.transpose());  // area-weighted
}

double quadricError(const Quadric& q, const Vec3& x) {
  const Eigen::Vector4d h(x.x(), x.y(), x.z(), 1.0);
  return h.dot(q * h);
}

struct Candidate {
  double cost;
  int u, v;
  unsigned stamp;  // sum of the two vertices' versions when queued; stale entries are skipped
  Vec3 target;
  bool operator<(const Candidate& o) const { return cost > o.cost; }  // min-heap
};

class Simplifier {
 public:
  explicit Simplifier(const TriMesh& mesh) : pos_(mesh.vertices), faces_(mesh.faces) {
    const int n = mesh.numVertices();
    faceAlive_.assign(faces_.size(), 1);
    vertexFaces_.resize(n);
    quadric_.assign(n, Quadric::Zero());
    version_.assign(n, 0);
    for (int f = 0; f < static_cast<int>(faces_.size()); ++f) {
      const Tri& t = faces_[f];
      const Quadric q = planeQuadric(pos_[t[0]], pos_[t[1]], pos_[t[2]]);
      for (int k = 0; k < 3; ++k) {
        vertexFaces_[t[k]].push_back(f);
        quadric_[t[k]] += q;
      }
    }
    aliveFaces_ = static_cast<int>(faces_.size());
  }

  void run(int targetFaces) {
    for (int f = 0; f < static_cast<int>(faces_.size()); ++f) {
      for (int k = 0; k < 3; ++k) {
        const int a = faces_[f][k], b = faces_[f][(k + 1) % 3];
        if (a < b) push(a, b);
      }
    }
    while (aliveFaces_ > targetFaces && !heap_.empty()) {
      const Candidate c = heap_.top();
      heap_.pop();
      if (c.stamp != version_[c.u] + version_[c.v] || removed(c.u) || removed(c.v)) continue;
      collapse(c);
    }
  }

  TriMesh result() const {
    TriMesh out;
    std::vector<int> map(pos_.size(), -1);
    for (size_t f = 0; f < faces_.size(); ++f) {
      if (!faceAlive_[f]) continue;
      Tri t = faces_[f];
      for (int& v : t) {
        if (map[v] < 0) {
          map[v] = out.numVertices();
          out.vertices.push_back(pos_[v]);
        }
        v = map[v];
      }
      out.faces.push_back(t);
    }
    return out;
  }

 private:
  bool removed(int v) const { return vertexFaces_[v].empty(); }

  void push(int u, int v) {
    const Quadric q = quadric_[u] + quadric_[v];
    // Optimal point: minimize the quadric; fall back to the best of the ends and the midpoint.
    Vec3 best = 0.5 * (pos_[u] + pos_[v]);
    double bestCost = quadricError(q, best);
    const Eigen::Matrix3d a = q.topLeftCorner<3, 3>();
    const Eigen::FullPivLU<Eigen::Matrix3d> lu(a);
    if (lu.rank() == 3) {
      const Vec3 x = lu.solve(-q.topRightCorner<3, 1>());
      const double e = quadricError(q, x);
      // Only trust the optimum near the edge: far away it is an ill-conditioned guess.
      if ((x - best).norm() < 2.0 * (pos_[u] - pos_[v]).norm() && e < bestCost) {
        best = x;
        bestCost = e;
      }
    }
    for (const Vec3& p : {pos_[u], pos_[v]}) {
      const double e = quadricError(q, p);
      if (e < bestCost) {
        best = p;
        bestCost = e;
      }
    }
    heap_.push({std::max(bestCost, 0.0), u, v, version_[u] + version_[v], best});
  }

  std::vector<int> neighbours(int v) const {
    std::vector<int> out;
    for (int f : vertexFaces_[v]) {
      for (int w : faces_[f]) {
        if (w != v) out.push_back(w);
      }
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }

  bool valid(const Candidate& c) const {
    const std::vector<int> nu = neighbours(c.u), nv = neighbours(c.v);
    std::vector<int> common;
    std::set_intersection(nu.begin(), nu.end(), nv.begin(), nv.end(), std::back_inserter(common));
    if (common.size() != 2) return false;             // link condition on a closed manifold
    if (nu.size() + nv.size() - 4 < 3) return false;  // the merged vertex keeps >= 3 faces
    // No face around u or v (other than the two that vanish) may flip or become a sliver.
    for (int w : {c.u, c.v}) {
      for (int f : vertexFaces_[w]) {
        const Tri& t = faces_[f];
        const bool hasU = t[0] == c.u || t[1] == c.u || t[2] == c.u;
        const bool hasV = t[0] == c.v || t[1] == c.v || t[2] == c.v;
        if (hasU && hasV) continue;
        Vec3 p[3];
        for (int k = 0; k < 3; ++k) p[k] = (t[k] == w) ? c.target : pos_[t[k]];
        const Vec3 before = (pos_[t[1]] - pos_[t[0]]).cross(pos_[t[2]] - pos_[t[0]]);
        const Vec3 after = (p[1] - p[0]).cross(p[2] - p[0]);
        const double longest = std::max({(p[1] - p[0]).squaredNorm(), (p[2] - p[1]).squaredNorm(),
                                         (p[0] - p[2]).squaredNorm()});
        if (after.dot(before) <= 0.2 * after.norm() * before.norm()) return false;
        if (after.norm() < 0.05 * longest) return false;  // sliver (aspect worse than ~35:1)
      }
    }
    return true;
  }

  void collapse(const Candidate& c) {
    if (!valid(c)) return;
    const int u = c.u, v = c.v;
    pos_[u] = c.target;
    quadric_[u] += quadric_[v];
    for (int f : vertexFaces_[v]) {
      Tri& t = faces_[f];
      const bool hasU = t[0] == u || t[1] == u || t[2] == u;
      if (hasU) {  // the two faces on edge (u, v) vanish
        faceAlive_[f] = 0;
        --aliveFaces_;
        for (int w : t) {
          if (w != v) {
            auto& list = vertexFaces_[w];
            list.erase(std::remove(list.begin(), list.end(), f), list.end());
          }
        }
      } else {
        for (int& w : t) {
          if (w == v) w = u;
        }
        vertexFaces_[u].push_back(f);
      }
    }
    vertexFaces_[v].clear();
    ++version_[u];
    ++version_[v];
    for (int w : neighbours(u)) {
      ++version_[w];
    }
    for (int w : neighbours(u)) {
      for (int x : neighbours(w)) push(std::min(w, x), std::max(w, x));
    }
  }

  std::vector<Vec3> pos_;
  std::vector<Tri> faces_;
  std::vector<char> faceAlive_;
  std::vector<std::vector<int>> vertexFaces_;
  std::vector<Quadric> quadric_;
  std::vector<unsigned> version_;
  std::priority_queue<Candidate> heap_;
  int aliveFaces_ = 0;
};

}  // namespace

TriMesh simplifySurface(const TriMesh& mesh, int targetFaces) {
  if (targetFaces >= mesh.numFaces()) return mesh;
  Simplifier s(mesh);
  s.run(std::max(targetFaces, 4));
  return s.result();
}

}  // namespace galsculpt

#include "solver/mesh/surface_checks.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <unordered_map>

#include "solver/mesh/union_find.h"

namespace galsculpt {

namespace {

struct DirectedEdge {
  Edge key;      // sorted
  bool forward;  // traversed from key[0] to key[1]
};

// Orientation of d against the plane (a, b, c), with a dead zone relative to `scale`, the size of
// the two triangles being compared, so that touching and coplanar configurations count as zero.
// Relative to the triangles and not to the mesh: a dead zone of the mesh's size swallowed small
// crack faces folded through their neighbours by a hundredth of their size (TetGen found them).
int orientSign(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, double scale) {
  const double v = tetSixVolume(a, b, c, d);
  const double eps = 1e-10 * scale * scale * scale;
  return v > eps ? 1 : (v < -eps ? -1 : 0);
}

bool segmentCrossesTriangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b,
                            const Vec3& c, double scale) {
  const int sp = orientSign(a, b, c, p, scale);
  const int sq = orientSign(a, b, c, q, scale);
  if (sp == 0 || sq == 0 || sp == sq) return false;
  const int s1 = orientSign(p, q, a, b, scale);
  const int s2 = orientSign(p, q, b, c, scale);
  const int s3 = orientSign(p, q, c, a, scale);
  return s1 != 0 && s1 == s2 && s2 == s3;
}

bool trianglesCross(const TriMesh& m, const Tri& f, const Tri& g) {
  const auto& v = m.vertices;
  Vec3 lo = v[f[0]], hi = v[f[0]];
  for (const Tri* t : {&f, &g}) {
    for (int k : *t) {
      lo = lo.cwiseMin(v[k]);
      hi = hi.cwiseMax(v[k]);
    }
  }
  const double scale = (hi - lo).norm();
  for (int i = 0; i < 3; ++i) {
    if (segmentCrossesTriangle(v[f[i]], v[f[(i + 1) % 3]], v[g[0]], v[g[1]], v[g[2]], scale))
      return true;
    if (segmentCrossesTriangle(v[g[i]], v[g[(i + 1) % 3]], v[f[0]], v[f[1]], v[f[2]], scale))
      return true;
  }
  return false;
}

}  // namespace

std::string SurfaceTopology::describeProblem() const {
  auto edge = [](const Edge& e) {
    std::ostringstream s;
    s << '(' << e[0] << ", " << e[1] << ')';
    return s.str();
  };
  if (degenerateFaces > 0) {
    return "degenerate: " + std::to_string(degenerateFaces) +
           " face(s) with zero area or a repeated vertex";
  }
  if (nonManifoldEdges > 0) {
    return "non-manifold: " + std::to_string(nonManifoldEdges) +
           " edge(s) shared by three or more faces, e.g. " + edge(firstNonManifoldEdge);
  }
  if (boundaryEdges > 0) {
    return "open: " + std::to_string(boundaryEdges) + " boundary edge(s), e.g. between vertices " +
           edge(firstBoundaryEdge);
  }
  if (nonManifoldVertices > 0) {
    return "non-manifold: " + std::to_string(nonManifoldVertices) +
           " vertex(es) where separate sheets touch";
  }
  if (inconsistentEdges > 0) {
    return "inconsistently oriented: " + std::to_string(inconsistentEdges) +
           " edge(s) whose two faces point opposite ways";
  }
  return {};
}

SurfaceTopology analyzeSurface(const TriMesh& mesh) {
  SurfaceTopology topo;
  std::vector<DirectedEdge> edges;
  edges.reserve(mesh.faces.size() * 3);
  const int n = mesh.numVertices();
  for (const Tri& f : mesh.faces) {
    bool bad = false;
    for (int k = 0; k < 3; ++k) bad |= (f[k] < 0 || f[k] >= n);
    if (bad || f[0] == f[1] || f[1] == f[2] || f[0] == f[2]) {
      ++topo.degenerateFaces;
      continue;
    }
    const Vec3 normal = (mesh.vertices[f[1]] - mesh.vertices[f[0]])
                            .cross(mesh.vertices[f[2]] - mesh.vertices[f[0]]);
    const double longest = std::max({(mesh.vertices[f[1]] - mesh.vertices[f[0]]).squaredNorm(),
                                     (mesh.vertices[f[2]] - mesh.vertices[f[1]]).squaredNorm(),
                                     (mesh.vertices[f[0]] - mesh.vertices[f[2]]).squaredNorm()});
    if (!(normal.norm() > 1e-14 * longest)) ++topo.degenerateFaces;
    for (int k = 0; k < 3; ++k) {
      const int a = f[k], b = f[(k + 1) % 3];
      edges.push_back({Edge{std::min(a, b), std::max(a, b)}, a < b});
    }
  }
  std::sort(edges.begin(), edges.end(),
            [](const DirectedEdge& x, const DirectedEdge& y) { return x.key < y.key; });
  for (size_t i = 0; i < edges.size();) {
    size_t j = i;
    int forward = 0;
    while (j < edges.size() && edges[j].key == edges[i].key) forward += edges[j++].forward;
    const size_t count = j - i;
    if (count == 1) {
      if (topo.boundaryEdges++ == 0) topo.firstBoundaryEdge = edges[i].key;
    } else if (count > 2) {
      if (topo.nonManifoldEdges++ == 0) topo.firstNonManifoldEdge = edges[i].key;
    } else if (forward != 1) {
      ++topo.inconsistentEdges;
    }
    i = j;
  }

  // A vertex is manifold when the opposite edges of its faces (its link) form one connected fan.
  std::vector<std::array<int, 3>> link;  // (vertex, x, y)
  link.reserve(mesh.faces.size() * 3);
  for (const Tri& f : mesh.faces) {
    if (f[0] == f[1] || f[1] == f[2] || f[0] == f[2]) continue;
    for (int k = 0; k < 3; ++k) link.push_back({f[k], f[(k + 1) % 3], f[(k + 2) % 3]});
  }
  std::sort(link.begin(), link.end());
  std::unordered_map<int, int> local;
  for (size_t i = 0; i < link.size();) {
    size_t j = i;
    while (j < link.size() && link[j][0] == link[i][0]) ++j;
    local.clear();
    for (size_t k = i; k < j; ++k) {
      local.emplace(link[k][1], static_cast<int>(local.size()));
      local.emplace(link[k][2], static_cast<int>(local.size()));
    }
    UnionFind uf(static_cast<int>(local.size()));
    int components = static_cast<int>(local.size());
    for (size_t k = i; k < j; ++k) components -= uf.unite(local[link[k][1]], local[link[k][2]]);
    if (components > 1) ++topo.nonManifoldVertices;
    i = j;
  }
  topo.pieces = countSurfacePieces(mesh);
  return topo;
}

double enclosedVolume(const TriMesh& mesh) {
  double sum = 0.0;
  for (const Tri& f : mesh.faces) {
    sum += mesh.vertices[f[0]].dot(mesh.vertices[f[1]].cross(mesh.vertices[f[2]]));
  }
  return sum / 6.0;
}

std::vector<double> enclosedVolumes(const TriMesh& mesh, const std::vector<int>& groupOfFace,
                                    int groups) {
  std::vector<double> sum(groups, 0.0);
  for (int fi = 0; fi < mesh.numFaces(); ++fi) {
    const Tri& f = mesh.faces[fi];
    sum[groupOfFace[fi]] += mesh.vertices[f[0]].dot(mesh.vertices[f[1]].cross(mesh.vertices[f[2]]));
  }
  for (double& v : sum) v /= 6.0;
  return sum;
}

double surfaceArea(const TriMesh& mesh) {
  double sum = 0.0;
  for (const Tri& f : mesh.faces) {
    sum += 0.5 * (mesh.vertices[f[1]] - mesh.vertices[f[0]])
                     .cross(mesh.vertices[f[2]] - mesh.vertices[f[0]])
                     .norm();
  }
  return sum;
}

int countSurfacePieces(const TriMesh& mesh, std::vector<int>* pieceOfFace) {
  UnionFind uf(mesh.numVertices());
  for (const Tri& f : mesh.faces) {
    uf.unite(f[0], f[1]);
    uf.unite(f[0], f[2]);
  }
  std::vector<int> rootLabel(mesh.vertices.size(), -1);
  std::vector<int> label(mesh.faces.size());
  int pieces = 0;
  for (size_t i = 0; i < mesh.faces.size(); ++i) {
    const int r = uf.find(mesh.faces[i][0]);
    if (rootLabel[r] < 0) rootLabel[r] = pieces++;
    label[i] = rootLabel[r];
  }
  if (pieceOfFace) *pieceOfFace = std::move(label);
  return pieces;
}

std::vector<std::pair<int, int>> findSelfIntersections(const TriMesh& mesh, size_t maxPairs,
                                                       const std::vector<char>* faceMask) {
  std::vector<std::pair<int, int>> hits;
  if (mesh.faces.empty()) return hits;
  const BoundingBox box = boundingBox(mesh.vertices);
  const double scale = std::max(box.size().maxCoeff(), 1e-300);
  // Grid cells of about two mean edge lengths: each face touches a few cells.
  double meanEdge = 0.0;
  for (const Tri& f : mesh.faces) meanEdge += (mesh.vertices[f[1]] - mesh.vertices[f[0]]).norm();
  meanEdge /= static_cast<double>(mesh.faces.size());
  const double cell = std::max(2.0 * meanEdge, scale / 256.0);
  const Eigen::Array3i dims =
      ((box.size().array() / cell).floor().cast<int>() + 1).min(1024).max(1);
  auto cellOf = [&](const Vec3& p) {
    return ((p - box.min).array() / cell).floor().cast<int>().max(0).min(dims - 1).eval();
  };
  std::vector<std::pair<long long, int>> entries;
  std::vector<Eigen::Array3i> lowest(mesh.faces.size());  // each face's lowest cell
  for (int fi = 0; fi < mesh.numFaces(); ++fi) {
    const Tri& f = mesh.faces[fi];
    const Vec3& a = mesh.vertices[f[0]];
    const Vec3& b = mesh.vertices[f[1]];
    const Vec3& c = mesh.vertices[f[2]];
    const Eigen::Array3i lo = cellOf(a.cwiseMin(b).cwiseMin(c));
    const Eigen::Array3i hi = cellOf(a.cwiseMax(b).cwiseMax(c));
    lowest[fi] = lo;
    for (int z = lo.z(); z <= hi.z(); ++z) {
      for (int y = lo.y(); y <= hi.y(); ++y) {
        for (int x = lo.x(); x <= hi.x(); ++x) {
          entries.push_back({(static_cast<long long>(z) * dims.y() + y) * dims.x() + x, fi});
        }
      }
    }
  }
  std::sort(entries.begin(), entries.end());
  // Faces that cross share a point, so their boxes overlap: most pairs of a cell are told apart
  // by their boxes alone.
  std::vector<BoundingBox> boxes(mesh.faces.size());
  for (int fi = 0; fi < mesh.numFaces(); ++fi) {
    const Tri& f = mesh.faces[fi];
    const Vec3 &a = mesh.vertices[f[0]], &b = mesh.vertices[f[1]], &c = mesh.vertices[f[2]];
    boxes[fi].min = a.cwiseMin(b).cwiseMin(c);
    boxes[fi].max = a.cwiseMax(b).cwiseMax(c);
  }
  auto apart = [&](int fi, int gi) {
    const BoundingBox& bf = boxes[fi];
    const BoundingBox& bg = boxes[gi];
    return (bf.max.array() < bg.min.array()).any() || (bg.max.array() < bf.min.array()).any();
  };
  // A pair of faces is listed once, in the first cell the two share (their lowest cells' corner).
  auto firstShared = [&](int fi, int gi) {
    const Eigen::Array3i c = lowest[fi].max(lowest[gi]);
    return (static_cast<long long>(c.z()) * dims.y() + c.y()) * dims.x() + c.x();
  };
  std::vector<std::pair<int, int>> candidates;
  for (size_t i = 0; i < entries.size();) {
    size_t j = i;
    while (j < entries.size() && entries[j].first == entries[i].first) ++j;
    for (size_t a = i; a < j; ++a) {
      for (size_t b = a + 1; b < j; ++b) {
        const int fi = entries[a].second, gi = entries[b].second;
        if (faceMask && !(*faceMask)[fi] && !(*faceMask)[gi]) continue;
        if (!apart(fi, gi) && firstShared(fi, gi) == entries[i].first)
          candidates.push_back({fi, gi});
      }
    }
    i = j;
  }
  std::sort(candidates.begin(), candidates.end());
  for (const auto& [fi, gi] : candidates) {
    const Tri& f = mesh.faces[fi];
    const Tri& g = mesh.faces[gi];
    int shared = 0;
    for (int a : f) shared += (a == g[0]) + (a == g[1]) + (a == g[2]);
    if (shared >= 2) continue;
    if (trianglesCross(mesh, f, g)) {
      hits.push_back({fi, gi});
      if (hits.size() >= maxPairs) break;
    }
  }
  return hits;
}

}  // namespace galsculpt

#include "solver/mesh/tet_mesh.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "solver/mesh/union_find.h"

namespace galsculpt {

bool isFlatTet(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3* p[4] = {&a, &b, &c, &d};
  double longest = 0.0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) longest = std::max(longest, (*p[i] - *p[j]).norm());
  // Written so that a NaN reads as flat.
  return !(std::abs(tetSixVolume(a, b, c, d)) > 1e-10 * longest * longest * longest);
}

double tetVolume(const TetMesh& mesh, int tet) {
  const Tet& t = mesh.tets[tet];
  const auto& v = mesh.vertices;
  return tetSixVolume(v[t[0]], v[t[1]], v[t[2]], v[t[3]]) / 6.0;
}

double totalVolume(const TetMesh& mesh) {
  double sum = 0.0;
  for (int t = 0; t < mesh.numTets(); ++t) sum += tetVolume(mesh, t);
  return sum;
}

std::array<Tri, 4> tetFacesOutward(const Tet& t) {
  return {Tri{t[1], t[2], t[3]}, Tri{t[0], t[3], t[2]}, Tri{t[0], t[1], t[3]},
          Tri{t[0], t[2], t[1]}};
}

namespace {

// Every tet's four faces keyed by their sorted vertices, sorted by key: shared faces side by side.
struct KeyedFace {
  std::array<int, 3> key;
  int tet;
  int opposite;  // the local corner the face leaves out
};
std::vector<KeyedFace> sortedTetFaces(const TetMesh& mesh) {
  std::vector<KeyedFace> all;
  all.reserve(mesh.tets.size() * 4);
  for (size_t t = 0; t < mesh.tets.size(); ++t) {
    const std::array<Tri, 4> faces = tetFacesOutward(mesh.tets[t]);
    for (int k = 0; k < 4; ++k) {
      std::array<int, 3> key = faces[k];
      std::sort(key.begin(), key.end());
      all.push_back({key, static_cast<int>(t), k});
    }
  }
  std::sort(all.begin(), all.end(),
            [](const KeyedFace& a, const KeyedFace& b) { return a.key < b.key; });
  return all;
}

}  // namespace

std::vector<Tri> boundaryFaces(const TetMesh& mesh) {
  const std::vector<KeyedFace> all = sortedTetFaces(mesh);
  std::vector<Tri> out;
  for (size_t i = 0; i < all.size();) {
    size_t j = i + 1;
    while (j < all.size() && all[j].key == all[i].key) ++j;
    if (j - i == 1) out.push_back(tetFacesOutward(mesh.tets[all[i].tet])[all[i].opposite]);
    i = j;
  }
  return out;
}

std::vector<std::array<int, 4>> tetFaceNeighbours(const TetMesh& mesh) {
  std::vector<std::array<int, 4>> out(mesh.tets.size(), {-1, -1, -1, -1});
  const std::vector<KeyedFace> all = sortedTetFaces(mesh);
  for (size_t i = 0; i < all.size();) {
    size_t j = i + 1;
    while (j < all.size() && all[j].key == all[i].key) ++j;
    if (j - i == 2) {
      out[all[i].tet][all[i].opposite] = all[i + 1].tet;
      out[all[i + 1].tet][all[i + 1].opposite] = all[i].tet;
    }
    i = j;
  }
  return out;
}

TriMesh boundarySurface(const TetMesh& mesh, std::vector<int>* toTetVertex) {
  TriMesh surface;
  std::vector<int> map(mesh.vertices.size(), -1);
  std::vector<int> back;
  for (Tri f : boundaryFaces(mesh)) {
    for (int& v : f) {
      if (map[v] < 0) {
        map[v] = static_cast<int>(surface.vertices.size());
        surface.vertices.push_back(mesh.vertices[v]);
        back.push_back(v);
      }
      v = map[v];
    }
    surface.faces.push_back(f);
  }
  if (toTetVertex) *toTetVertex = std::move(back);
  return surface;
}

std::vector<Edge> uniqueEdges(const TetMesh& mesh) {
  std::vector<Edge> edges;
  edges.reserve(mesh.tets.size() * 6);
  for (const Tet& t : mesh.tets) {
    for (int i = 0; i < 4; ++i) {
      for (int j = i + 1; j < 4; ++j) {
        edges.push_back({std::min(t[i], t[j]), std::max(t[i], t[j])});
      }
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

BoundingBox boundingBox(const std::vector<Vec3>& points) {
  BoundingBox box;
  if (points.empty()) return box;
  box.min = box.max = points[0];
  for (const Vec3& p : points) {
    box.min = box.min.cwiseMin(p);
    box.max = box.max.cwiseMax(p);
  }
  return box;
}

double tetMeanRatio(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const double volume = tetSixVolume(a, b, c, d) / 6.0;
  const double sumSq = (b - a).squaredNorm() + (c - a).squaredNorm() + (d - a).squaredNorm() +
                       (c - b).squaredNorm() + (d - b).squaredNorm() + (d - c).squaredNorm();
  if (sumSq <= 0.0) return 0.0;
  // 12 (3|V|)^(2/3) / sum l^2 equals 1 for the regular tet.
  const double q = 12.0 * std::cbrt(9.0 * volume * volume) / sumSq;
  return volume < 0.0 ? -q : q;
}

int countPieces(const TetMesh& mesh, std::vector<int>* pieceOfVertex) {
  UnionFind uf(mesh.numVertices());
  std::vector<char> used(mesh.vertices.size(), 0);
  for (const Tet& t : mesh.tets) {
    for (int i = 0; i < 4; ++i) used[t[i]] = 1;
    uf.unite(t[0], t[1]);
    uf.unite(t[0], t[2]);
    uf.unite(t[0], t[3]);
  }
  std::vector<int> label(mesh.vertices.size(), -1);
  std::vector<int> rootLabel(mesh.vertices.size(), -1);
  int pieces = 0;
  for (int v = 0; v < mesh.numVertices(); ++v) {
    if (!used[v]) continue;
    const int r = uf.find(v);
    if (rootLabel[r] < 0) rootLabel[r] = pieces++;
    label[v] = rootLabel[r];
  }
  if (pieceOfVertex) *pieceOfVertex = std::move(label);
  return pieces;
}

std::vector<Vec3> vertexNormals(const std::vector<Vec3>& vertices, const std::vector<Tri>& faces) {
  std::vector<Vec3> normals(vertices.size(), Vec3::Zero());
  for (const Tri& f : faces) {
    // The cross product's length is twice the area: area weighting for free.
    const Vec3 n = (vertices[f[1]] - vertices[f[0]]).cross(vertices[f[2]] - vertices[f[0]]);
    for (int k = 0; k < 3; ++k) normals[f[k]] += n;
  }
  for (Vec3& n : normals) {
    const double len = n.norm();
    if (len > 0.0) n /= len;
  }
  return normals;
}

std::vector<Vec3> vertexNormals(const TriMesh& mesh) {
  return vertexNormals(mesh.vertices, mesh.faces);
}

}  // namespace galsculpt

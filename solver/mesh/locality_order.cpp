#include "solver/mesh/locality_order.h"

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <vector>

namespace galsculpt {

namespace {

// 21 bits of x spread to every third bit.
std::uint64_t spreadBits(std::uint64_t x) {
  x &= 0x1fffffull;
  x = (x | x << 32) & 0x1f00000000ffffull;
  x = (x | x << 16) & 0x1f0000ff0000ffull;
  x = (x | x << 8) & 0x100f00f00f00f00full;
  x = (x | x << 4) & 0x10c30c30c30c30c3ull;
  x = (x | x << 2) & 0x1249249249249249ull;
  return x;
}

// The point's Morton key in the box: 21 bits an axis.
std::uint64_t mortonKey(const Vec3& p, const BoundingBox& box) {
  constexpr double kCells = 2097151.0;  // 2^21 - 1
  std::uint64_t key = 0;
  for (int axis = 0; axis < 3; ++axis) {
    const double extent = box.max[axis] - box.min[axis];
    const double t = extent > 0.0 ? (p[axis] - box.min[axis]) / extent : 0.0;
    const auto cell = static_cast<std::uint64_t>(std::clamp(t, 0.0, 1.0) * kCells);
    key |= spreadBits(cell) << axis;
  }
  return key;
}

}  // namespace

void orderForLocality(TetMesh& mesh) {
  const int n = mesh.numVertices();
  if (n == 0) return;
  const BoundingBox box = boundingBox(mesh.vertices);
  std::vector<std::uint64_t> key(n);
  for (int v = 0; v < n; ++v) key[v] = mortonKey(mesh.vertices[v], box);
  std::vector<int> order(n);  // new index -> old
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return key[a] < key[b]; });
  std::vector<int> newIndex(n);
  for (int i = 0; i < n; ++i) newIndex[order[i]] = i;

  std::vector<Vec3> vertices(n);
  for (int i = 0; i < n; ++i) vertices[i] = mesh.vertices[order[i]];
  mesh.vertices = std::move(vertices);
  if (static_cast<int>(mesh.vertexMarkers.size()) == n) {
    std::vector<int> markers(n);
    for (int i = 0; i < n; ++i) markers[i] = mesh.vertexMarkers[order[i]];
    mesh.vertexMarkers = std::move(markers);
  }
  for (Tri& f : mesh.faces)
    for (int& v : f) v = newIndex[v];
  for (Tet& t : mesh.tets)
    for (int& v : t) v = newIndex[v];

  // Tets by their corners, smallest first (each tet's corners sorted once, as its key; a stable
  // sort, so that equal sets keep their order).
  const int m = mesh.numTets();
  std::vector<Tet> corners(mesh.tets);
  for (Tet& c : corners) std::sort(c.begin(), c.end());
  std::vector<int> tetOrder(m);
  std::iota(tetOrder.begin(), tetOrder.end(), 0);
  std::stable_sort(tetOrder.begin(), tetOrder.end(),
                   [&](int a, int b) { return corners[a] < corners[b]; });
  std::vector<Tet> tets(m);
  for (int i = 0; i < m; ++i) tets[i] = mesh.tets[tetOrder[i]];
  mesh.tets = std::move(tets);
}

}  // namespace galsculpt

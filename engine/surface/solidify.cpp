#include "engine/surface/solidify.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <unordered_map>
#include <vector>

#include "engine/surface/surface_bvh.h"
#include "solver/mesh/exact_predicates.h"

namespace galsculpt {

namespace {

struct Grid {
  Vec3 origin = Vec3::Zero();
  double cell = 0.0;
  std::array<long long, 3> n{};
  long long nodes() const { return n[0] * n[1] * n[2]; }
  long long index(long long i, long long j, long long k) const { return i + n[0] * (j + n[1] * k); }
  Vec3 position(long long i, long long j, long long k) const {
    return origin +
           cell * Vec3(static_cast<double>(i), static_cast<double>(j), static_cast<double>(k));
  }
};

Grid makeGrid(const TriMesh& surface, const SolidifyOptions& options) {
  Vec3 lo = surface.vertices[0], hi = surface.vertices[0];
  for (const Vec3& p : surface.vertices) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  Grid grid;
  grid.cell = options.cell;
  for (;;) {
    // Off the round positions a modelled surface tends to have, so that no column runs along a
    // face's edge or through a vertex in practice (ties are still broken consistently).
    const Vec3 offset = grid.cell * Vec3(1.5 + 0.0123457, 1.5 + 0.0234568, 1.5 + 0.0345679);
    grid.origin = lo - offset;
    for (int a = 0; a < 3; ++a)
      grid.n[a] = static_cast<long long>(std::floor((hi[a] - grid.origin[a]) / grid.cell)) + 3;
    if (grid.nodes() <= options.maxNodes) return grid;
    grid.cell *= 1.01 * std::cbrt(static_cast<double>(grid.nodes()) / options.maxNodes);
  }
}

double orient2(double ax, double ay, double bx, double by, double px, double py) {
  return (bx - ax) * (py - ay) - (by - ay) * (px - ax);
}

// The sign of orient2 (u, v, (px, py)) exactly: the plane z = 0 lifted against a point above
// it (exact_predicates.h's orient3d is negative where the three points turn counter-clockwise
// seen from above).
int exactOrient2(const Vec3& u, const Vec3& v, double px, double py) {
  return -orient3d(Vec3(u.x(), u.y(), 0.0), Vec3(v.x(), v.y(), 0.0), Vec3(px, py, 0.0),
                   Vec3(u.x(), u.y(), 1.0));
}

// Of a counter-clockwise triangle's edge u -> v: whether a point on it counts as inside (the
// top-left rule), so that a column through an edge two faces share crosses exactly one of them.
bool topLeft(double ux, double uy, double vx, double vy) {
  return (uy == vy && vx < ux) || vy < uy;
}

// Winding number of `surface` at every node: per column of nodes along z, the signed crossings
// of the faces below each node.
std::vector<int> windingNumbers(const TriMesh& surface, const Grid& grid) {
  const long long columns = grid.n[0] * grid.n[1];
  struct Crossing {
    double z;
    int delta;
  };
  std::vector<std::vector<Crossing>> crossings(static_cast<size_t>(columns));
  for (const Tri& f : surface.faces) {
    Vec3 a = surface.vertices[f[0]], b = surface.vertices[f[1]], c = surface.vertices[f[2]];
    const double nz = (b - a).cross(c - a).z();
    if (nz == 0.0) continue;  // parallel to the columns: crossed by none
    // Entering the solid upwards means crossing a face whose outward normal points down.
    const int delta = nz < 0.0 ? 1 : -1;
    if (nz < 0.0) std::swap(b, c);  // counter-clockwise seen from above
    const double minX = std::min({a.x(), b.x(), c.x()}), maxX = std::max({a.x(), b.x(), c.x()});
    const double minY = std::min({a.y(), b.y(), c.y()}), maxY = std::max({a.y(), b.y(), c.y()});
    const long long i0 =
        std::max(0LL, static_cast<long long>(std::ceil((minX - grid.origin.x()) / grid.cell)));
    const long long i1 = std::min(
        grid.n[0] - 1, static_cast<long long>(std::floor((maxX - grid.origin.x()) / grid.cell)));
    const long long j0 =
        std::max(0LL, static_cast<long long>(std::ceil((minY - grid.origin.y()) / grid.cell)));
    const long long j1 = std::min(
        grid.n[1] - 1, static_cast<long long>(std::floor((maxY - grid.origin.y()) / grid.cell)));
    for (long long j = j0; j <= j1; ++j) {
      const double py = grid.origin.y() + grid.cell * static_cast<double>(j);
      for (long long i = i0; i <= i1; ++i) {
        const double px = grid.origin.x() + grid.cell * static_cast<double>(i);
        // Inside by exact signs (a column through an edge two faces share is decided alike for
        // both), the crossing's height by floating-point weights.
        const int sa = exactOrient2(b, c, px, py), sb = exactOrient2(c, a, px, py),
                  sc = exactOrient2(a, b, px, py);
        const bool inside = (sa > 0 || (sa == 0 && topLeft(b.x(), b.y(), c.x(), c.y()))) &&
                            (sb > 0 || (sb == 0 && topLeft(c.x(), c.y(), a.x(), a.y()))) &&
                            (sc > 0 || (sc == 0 && topLeft(a.x(), a.y(), b.x(), b.y())));
        if (!inside) continue;
        const double wa = std::max(0.0, orient2(b.x(), b.y(), c.x(), c.y(), px, py));
        const double wb = std::max(0.0, orient2(c.x(), c.y(), a.x(), a.y(), px, py));
        const double wc = std::max(0.0, orient2(a.x(), a.y(), b.x(), b.y(), px, py));
        const double sum = wa + wb + wc;
        if (!(sum > 0.0)) continue;
        const double z = (wa * a.z() + wb * b.z() + wc * c.z()) / sum;
        crossings[static_cast<size_t>(i + grid.n[0] * j)].push_back({z, delta});
      }
    }
  }
  std::vector<int> winding(static_cast<size_t>(grid.nodes()), 0);
  for (long long j = 0; j < grid.n[1]; ++j) {
    for (long long i = 0; i < grid.n[0]; ++i) {
      std::vector<Crossing>& column = crossings[static_cast<size_t>(i + grid.n[0] * j)];
      std::sort(column.begin(), column.end(),
                [](const Crossing& p, const Crossing& q) { return p.z < q.z; });
      size_t next = 0;
      int w = 0;
      for (long long k = 0; k < grid.n[2]; ++k) {
        const double z = grid.origin.z() + grid.cell * static_cast<double>(k);
        while (next < column.size() && column[next].z < z) w += column[next++].delta;
        winding[static_cast<size_t>(grid.index(i, j, k))] = w;
      }
    }
  }
  return winding;
}

// Where along p -> q (as a fraction) the winding number, `windingAtP` at p, crosses between
// inside (>= 1) and outside: the surface's crossings of the segment met in order, each entering
// (+1, against the face's normal) or leaving (-1). Empty when they do not account for the
// change (the segment grazes an edge or a vertex).
std::optional<double> exactCrossing(const TriMesh& surface, const SurfaceBvh& bvh, const Vec3& p,
                                    const Vec3& q, int windingAtP) {
  const double length = (q - p).norm();
  const Vec3 direction = (q - p) / length;
  const bool startInside = windingAtP >= 1;
  int winding = windingAtP;
  double t = 0.0;
  for (int hits = 0; hits < 64 && t < length; ++hits) {
    const auto hit = bvh.intersect(surface, p + t * direction, direction, length - t);
    if (!hit) return std::nullopt;
    t += hit->distance;
    winding += hit->normal.dot(direction) < 0.0 ? 1 : -1;
    if ((winding >= 1) != startInside) return t / length;
    t += 1e-9 * length;  // past the face just met
  }
  return std::nullopt;
}

// The six tets of a cube about its main diagonal (corner bits: x = 1, y = 2, z = 4).
constexpr std::array<std::array<int, 4>, 6> kCubeTets = {{
    {0, 1, 3, 7},
    {0, 1, 5, 7},
    {0, 2, 3, 7},
    {0, 2, 6, 7},
    {0, 4, 5, 7},
    {0, 4, 6, 7},
}};

}  // namespace

TriMesh solidify(const TriMesh& surface, const SolidifyOptions& options) {
  if (!(options.cell > 0.0)) throw std::invalid_argument("solidify: the cell must be positive");
  TriMesh out;
  if (surface.faces.empty()) return out;
  const Grid grid = makeGrid(surface, options);
  const std::vector<int> winding = windingNumbers(surface, grid);
  auto inside = [&](long long node) { return winding[static_cast<size_t>(node)] >= 1; };

  // Where a crossed edge's own crossings do not tell where the boundary is: the signed distance
  // at its ends, found when first needed.
  SurfaceBvh bvh;
  bvh.build(surface);
  std::vector<double> field(static_cast<size_t>(grid.nodes()), 0.0);
  std::vector<char> known(static_cast<size_t>(grid.nodes()), 0);
  auto corner = [&](long long i, long long j, long long k, int bits) {
    return grid.index(i + (bits & 1), j + ((bits >> 1) & 1), k + ((bits >> 2) & 1));
  };
  auto valueAt = [&](long long node, long long i, long long j, long long k, int bits) {
    if (!known[static_cast<size_t>(node)]) {
      const Vec3 p = grid.position(i + (bits & 1), j + ((bits >> 1) & 1), k + ((bits >> 2) & 1));
      const double d = std::max(bvh.distance(surface, p), 1e-9 * grid.cell);
      field[static_cast<size_t>(node)] = inside(node) ? d : -d;
      known[static_cast<size_t>(node)] = 1;
    }
    return field[static_cast<size_t>(node)];
  };

  std::unordered_map<long long, int> vertexOfEdge;
  const long long nodes = grid.nodes();
  for (long long k = 0; k + 1 < grid.n[2]; ++k) {
    for (long long j = 0; j + 1 < grid.n[1]; ++j) {
      for (long long i = 0; i + 1 < grid.n[0]; ++i) {
        std::array<long long, 8> node;
        int insideCount = 0;
        for (int bits = 0; bits < 8; ++bits) {
          node[bits] = corner(i, j, k, bits);
          insideCount += inside(node[bits]);
        }
        if (insideCount == 0 || insideCount == 8) continue;
        std::array<Vec3, 8> position;
        for (int bits = 0; bits < 8; ++bits)
          position[bits] =
              grid.position(i + (bits & 1), j + ((bits >> 1) & 1), k + ((bits >> 2) & 1));
        auto value = [&](int bits) { return valueAt(node[bits], i, j, k, bits); };
        auto edgeVertex = [&](int p, int q) {
          const long long a = std::min(node[p], node[q]), b = std::max(node[p], node[q]);
          const auto [it, added] =
              vertexOfEdge.try_emplace(a * nodes + b, static_cast<int>(out.vertices.size()));
          if (added) {
            // On the surface where the segment meets it; otherwise the distance field's zero.
            const std::optional<double> exact = exactCrossing(
                surface, bvh, position[p], position[q], winding[static_cast<size_t>(node[p])]);
            const double t = std::clamp(exact ? *exact : value(p) / (value(p) - value(q)),
                                        options.nodeClearance, 1.0 - options.nodeClearance);
            out.vertices.push_back(position[p] + t * (position[q] - position[p]));
          }
          return it->second;
        };
        for (const auto& tet : kCubeTets) {
          std::array<int, 4> in{}, outside{};
          int nIn = 0, nOut = 0;
          for (int c : tet) {
            if (inside(node[c]))
              in[nIn++] = c;
            else
              outside[nOut++] = c;
          }
          if (nIn == 0 || nOut == 0) continue;
          Vec3 centreIn = Vec3::Zero(), centreOut = Vec3::Zero();
          for (int m = 0; m < nIn; ++m) centreIn += position[in[m]] / nIn;
          for (int m = 0; m < nOut; ++m) centreOut += position[outside[m]] / nOut;
          auto emit = [&](int a, int b, int c) {
            Tri tri{a, b, c};
            const Vec3 normal =
                (out.vertices[b] - out.vertices[a]).cross(out.vertices[c] - out.vertices[a]);
            if (normal.dot(centreOut - centreIn) < 0.0) std::swap(tri[1], tri[2]);
            out.faces.push_back(tri);
          };
          if (nIn == 1 || nOut == 1) {
            const bool loneInside = nIn == 1;
            const int lone = loneInside ? in[0] : outside[0];
            const std::array<int, 4>& others = loneInside ? outside : in;
            emit(edgeVertex(lone, others[0]), edgeVertex(lone, others[1]),
                 edgeVertex(lone, others[2]));
          } else {
            // Two in, two out: the quad through the four edges between them, in cyclic order.
            const int pr = edgeVertex(in[0], outside[0]), ps = edgeVertex(in[0], outside[1]);
            const int qs = edgeVertex(in[1], outside[1]), qr = edgeVertex(in[1], outside[0]);
            emit(pr, ps, qs);
            emit(pr, qs, qr);
          }
        }
      }
    }
  }
  return out;
}

}  // namespace galsculpt

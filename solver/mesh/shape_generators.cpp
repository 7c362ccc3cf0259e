#include "solver/mesh/shape_generators.h"

#include <cmath>
#include <map>
#include <random>
#include <vector>

namespace galsculpt {

namespace {

double unitFromBits(std::mt19937& gen) {
  return static_cast<double>(gen()) / 4294967296.0;
}

// Ear clipping for a simple counter-clockwise polygon; enough for the Charpy profile.
std::vector<Tri> triangulatePolygon(const std::vector<Eigen::Vector2d>& poly) {
  std::vector<int> idx(poly.size());
  for (size_t i = 0; i < poly.size(); ++i) idx[i] = static_cast<int>(i);
  auto cross = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
    return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
  };
  std::vector<Tri> tris;
  while (idx.size() > 3) {
    bool clipped = false;
    for (size_t i = 0; i < idx.size() && !clipped; ++i) {
      const int a = idx[(i + idx.size() - 1) % idx.size()], b = idx[i],
                c = idx[(i + 1) % idx.size()];
      if (cross(poly[a], poly[b], poly[c]) <= 0) continue;
      bool inside = false;
      for (int k : idx) {
        if (k == a || k == b || k == c) continue;
        if (cross(poly[a], poly[b], poly[k]) >= 0 && cross(poly[b], poly[c], poly[k]) >= 0 &&
            cross(poly[c], poly[a], poly[k]) >= 0) {
          inside = true;
          break;
        }
      }
      if (inside) continue;
      tris.push_back({a, b, c});
      idx.erase(idx.begin() + static_cast<long>(i));
      clipped = true;
    }
    if (!clipped) break;  // not simple; cannot happen for our fixed profiles
  }
  if (idx.size() == 3) tris.push_back({idx[0], idx[1], idx[2]});
  return tris;
}

}  // namespace

TriMesh makeIcosphere(double radius, int subdivisions) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  TriMesh m;
  m.vertices = {Vec3(-1, t, 0), Vec3(1, t, 0), Vec3(-1, -t, 0), Vec3(1, -t, 0),
                Vec3(0, -1, t), Vec3(0, 1, t), Vec3(0, -1, -t), Vec3(0, 1, -t),
                Vec3(t, 0, -1), Vec3(t, 0, 1), Vec3(-t, 0, -1), Vec3(-t, 0, 1)};
  m.faces = {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
             {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
             {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (Vec3& v : m.vertices) v.normalize();
  for (int s = 0; s < subdivisions; ++s) {
    std::map<std::pair<int, int>, int> midpoint;
    auto mid = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      auto it = midpoint.find(key);
      if (it != midpoint.end()) return it->second;
      m.vertices.push_back((m.vertices[a] + m.vertices[b]).normalized());
      const int id = m.numVertices() - 1;
      midpoint.emplace(key, id);
      return id;
    };
    std::vector<Tri> next;
    next.reserve(m.faces.size() * 4);
    for (const Tri& f : m.faces) {
      const int ab = mid(f[0], f[1]), bc = mid(f[1], f[2]), ca = mid(f[2], f[0]);
      next.push_back({f[0], ab, ca});
      next.push_back({f[1], bc, ab});
      next.push_back({f[2], ca, bc});
      next.push_back({ab, bc, ca});
    }
    m.faces = std::move(next);
  }
  for (Vec3& v : m.vertices) v *= radius;
  return m;
}

TriMesh makeCharpyBar() {
  const double length = 0.055, height = 0.010, width = 0.010, depth = 0.002;
  const double halfOpening = depth * std::tan(22.5 * M_PI / 180.0);  // 45-degree included angle
  const double c = 0.5 * length;
  const std::vector<Eigen::Vector2d> profile = {{0, 0},
                                                {length, 0},
                                                {length, height},
                                                {c + halfOpening, height},
                                                {c, height - depth},
                                                {c - halfOpening, height},
                                                {0, height}};
  const int n = static_cast<int>(profile.size());
  TriMesh m;
  for (double z : {0.0, width}) {
    for (const auto& p : profile) m.vertices.push_back(Vec3(p.x(), p.y(), z));
  }
  for (const Tri& t : triangulatePolygon(profile)) {
    m.faces.push_back({t[0], t[2], t[1]});              // z = 0 cap faces -z
    m.faces.push_back({t[0] + n, t[1] + n, t[2] + n});  // z = width cap faces +z
  }
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    m.faces.push_back({i, j, j + n});
    m.faces.push_back({i, j + n, i + n});
  }
  return m;
}

namespace {

// A superellipse meridian from the top pole (rho 0, h 1) over the rim (rho 1) to the bottom pole,
// sampled evenly by arc length in the scale (radius, thickness) of the slab: about one sample
// per `edgeLength`.
std::vector<Eigen::Vector2d> sampleMeridian(double exponent, double radius, double thickness,
                                            double edgeLength) {
  auto meridianPoint = [&](double u) {  // u in [0, pi]: angle of the superellipse parameter
    const double c = std::cos(u), s = std::sin(u);
    const double rho = std::pow(std::abs(s), 2.0 / exponent);
    const double h = std::copysign(std::pow(std::abs(c), 2.0 / exponent), c);
    return Eigen::Vector2d(rho, h);
  };
  const int fine = 20000;
  std::vector<Eigen::Vector2d> dense(fine + 1);
  std::vector<double> length(fine + 1, 0.0);
  for (int i = 0; i <= fine; ++i) dense[i] = meridianPoint(M_PI * i / fine);
  for (int i = 1; i <= fine; ++i) {
    const Eigen::Vector2d d = dense[i] - dense[i - 1];
    length[i] = length[i - 1] + std::hypot(d.x() * radius, d.y() * thickness);
  }
  const int segments = std::max(4, static_cast<int>(std::round(length[fine] / edgeLength)));
  std::vector<Eigen::Vector2d> meridian;
  int k = 0;
  for (int m = 0; m <= segments; ++m) {
    const double target = length[fine] * m / segments;
    while (k < fine && length[k + 1] < target) ++k;
    const double t = (k < fine && length[k + 1] > length[k])
                         ? (target - length[k]) / (length[k + 1] - length[k])
                         : 0.0;
    meridian.push_back(dense[k] + t * (dense[std::min(k + 1, fine)] - dense[k]));
  }
  meridian.front() = Eigen::Vector2d(0.0, 1.0);
  meridian.back() = Eigen::Vector2d(0.0, -1.0);
  return meridian;
}

// Triangles between consecutive rings of vertices (a ring of one vertex is a pole): always
// advance along the ring whose next vertex comes first in angle.
void zipRings(const std::vector<int>& ringStart, const std::vector<int>& ringSize, TriMesh& m) {
  for (size_t i = 0; i + 1 < ringStart.size(); ++i) {
    const int a0 = ringStart[i], na = ringSize[i], b0 = ringStart[i + 1], nb = ringSize[i + 1];
    int ia = 0, ib = 0;
    while (ia < na || ib < nb) {
      const double nextA = (ia + 1.0) / na, nextB = (ib + 1.0) / nb;
      const bool advanceA = (ib >= nb) || (ia < na && nextA <= nextB);
      const int va = a0 + ia % na, vb = b0 + ib % nb;
      if (advanceA) {
        const int va2 = a0 + (ia + 1) % na;
        if (va2 != va) m.faces.push_back({va, va2, vb});
        ++ia;
      } else {
        const int vb2 = b0 + (ib + 1) % nb;
        if (vb2 != vb) m.faces.push_back({va, vb2, vb});
        ++ib;
      }
    }
  }
}

}  // namespace

TriMesh makeSteakSlab(double edgeLength, std::uint32_t seed) {
  std::mt19937 gen(seed);
  struct Wave {
    int frequency;
    double phase, amplitude;
  };
  auto waves = [&](int count, double amplitude) {
    std::vector<Wave> w;
    for (int i = 0; i < count; ++i) {
      const int f = 2 + static_cast<int>(unitFromBits(gen) * 5.0);
      w.push_back({f, 2.0 * M_PI * unitFromBits(gen), amplitude * (0.5 + unitFromBits(gen)) / f});
    }
    return w;
  };
  const std::vector<Wave> outline = waves(5, 0.25);    // lumpy outline in the x-z plane
  const std::vector<Wave> thickness = waves(3, 0.35);  // uneven thickness
  auto sum = [](const std::vector<Wave>& w, double theta) {
    double s = 1.0;
    for (const Wave& x : w) s += x.amplitude * std::sin(x.frequency * theta + x.phase);
    return s;
  };
  const double halfLength = 0.100, halfWidth = 0.060, halfThickness = 0.015;
  const double exponent = 4.0;  // superellipse meridian: flat faces, rounded rim
  // Meridian samples in a typical 3D scale (mean of the two in-plane radii).
  const double meanRadius = 0.5 * (halfLength + halfWidth);
  const std::vector<Eigen::Vector2d> meridian =
      sampleMeridian(exponent, meanRadius, halfThickness, edgeLength);

  auto position = [&](double rho, double h, double theta) {
    const double r = rho * sum(outline, theta);
    const double lift = 0.12 * (1.0 - rho * rho);  // a gentle dome, larger in the middle
    // The thickness varies with the angle only away from the poles, where it would crease.
    const double t = 1.0 + (sum(thickness, theta) - 1.0) * rho * rho;
    return Vec3(r * halfLength * std::cos(theta), (h * t + lift * h) * halfThickness,
                r * halfWidth * std::sin(theta));
  };

  TriMesh m;
  std::vector<int> ringStart, ringSize;
  for (size_t i = 0; i < meridian.size(); ++i) {
    const double rho = meridian[i].x(), h = meridian[i].y();
    ringStart.push_back(m.numVertices());
    const bool pole = (i == 0 || i + 1 == meridian.size());
    const int n =
        pole
            ? 1
            : std::max(6, static_cast<int>(std::round(2.0 * M_PI * rho * meanRadius / edgeLength)));
    ringSize.push_back(n);
    for (int j = 0; j < n; ++j) m.vertices.push_back(position(rho, h, 2.0 * M_PI * j / n));
  }
  zipRings(ringStart, ringSize, m);
  double volume = 0.0;
  for (const Tri& f : m.faces)
    volume += m.vertices[f[0]].dot(m.vertices[f[1]].cross(m.vertices[f[2]]));
  if (volume < 0.0) {
    for (Tri& f : m.faces) std::swap(f[1], f[2]);
  }
  return m;
}

}  // namespace galsculpt

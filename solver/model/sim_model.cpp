#include "solver/model/sim_model.h"

#include <algorithm>
#include <numeric>

#include "solver/fem/material_table.h"
#include "solver/mesh/csr.h"
#include "solver/mesh/union_find.h"

namespace galsculpt {

namespace {

// Greedy colouring in tet order: deterministic, and a handful of colours for tet meshes.
std::vector<std::vector<int>> colorTets(const TetMesh& mesh) {
  std::vector<std::vector<int>> colors;
  std::vector<std::vector<int>> vertexColors(mesh.vertices.size());
  for (int t = 0; t < mesh.numTets(); ++t) {
    int c = 0;
    while (true) {
      bool free = true;
      for (int v : mesh.tets[t]) {
        const auto& used = vertexColors[v];
        if (std::find(used.begin(), used.end(), c) != used.end()) {
          free = false;
          break;
        }
      }
      if (free) break;
      ++c;
    }
    if (c >= static_cast<int>(colors.size())) colors.resize(c + 1);
    colors[c].push_back(t);
    for (int v : mesh.tets[t]) vertexColors[v].push_back(c);
  }
  return colors;
}

// Each vertex's element terms in colour order, each block's in element order.
void buildAssemblyLists(SimModel& m) {
  std::vector<std::vector<int>> perVertex(m.numVertices()), perBlock(m.numBlocks());
  for (const std::vector<int>& color : m.colors)
    for (int t : color)
      for (int a = 0; a < 4; ++a) perVertex[m.mesh.tets[t][a]].push_back(4 * t + a);
  for (int t = 0; t < m.numTets(); ++t)
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) perBlock[m.scatter[t][4 * a + b]].push_back(16 * t + 4 * a + b);
  flattenGroups(perVertex, m.vertexSlotStart, m.vertexSlots);
  flattenGroups(perBlock, m.blockSlotStart, m.blockSlots);
}

}  // namespace

Vec3 anchorOffset(const AnchorConstraint& anchor, double time) {
  const auto& p = anchor.path;
  if (p.empty()) return Vec3::Zero();
  if (time <= p.front().time) return p.front().offset;
  if (time >= p.back().time) return p.back().offset;
  const auto it = std::upper_bound(p.begin(), p.end(), time,
                                   [](double t, const AnchorKey& k) { return t < k.time; });
  const AnchorKey& b = *it;
  const AnchorKey& a = *(it - 1);
  const double u = (time - a.time) / (b.time - a.time);
  return (1.0 - u) * a.offset + u * b.offset;
}

Lame MaterialParams::elementLame() const {
  Lame out = lame;
  out.crackWidth = crackWidth;
  if (materialInfo(model).flowInEnergy && plastic.yieldStress > 0.0) {
    out.yield = plastic.yieldStress;
    out.hardening = plastic.hardening;
  }
  return out;
}

SimModel buildSimModel(const TetMesh& mesh, const MaterialParams& material) {
  SimModel m;
  m.mesh = mesh;
  m.material = material;
  const int n = mesh.numVertices();
  m.rest.reserve(mesh.tets.size());
  m.mass.assign(n, 0.0);
  for (const Tet& t : mesh.tets) {
    const TetPoints p{mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]],
                      mesh.vertices[t[3]]};
    m.rest.push_back(computeTetRest(p));
    for (int v : t) m.mass[v] += material.density * m.rest.back().volume / 4.0;
  }
  // A vertex in no tet is a free particle: give it the mean vertex mass so it still falls.
  const double total = std::accumulate(m.mass.begin(), m.mass.end(), 0.0);
  const double meanMass = n > 0 && total > 0.0 ? total / n : 1.0;
  for (double& mass : m.mass) {
    if (mass == 0.0) mass = meanMass;
  }
  m.edges = uniqueEdges(mesh);
  m.tetEdges.resize(mesh.tets.size());
  for (size_t t = 0; t < mesh.tets.size(); ++t) {
    for (int e = 0; e < 6; ++e) {
      const int a = mesh.tets[t][kTetEdges[e][0]], b = mesh.tets[t][kTetEdges[e][1]];
      const Edge key{std::min(a, b), std::max(a, b)};
      m.tetEdges[t][e] =
          static_cast<int>(std::lower_bound(m.edges.begin(), m.edges.end(), key) - m.edges.begin());
    }
  }
  m.pattern = buildBlockPattern(n, m.edges);
  m.scatter = buildTetScatter(m.pattern, mesh.tets);
  m.colors = colorTets(mesh);
  buildAssemblyLists(m);
  return m;
}

SimState initialState(const SimModel& model) {
  SimState s;
  s.x = model.mesh.vertices;
  s.v.assign(model.mesh.vertices.size(), Vec3::Zero());
  s.damaged.assign(model.edges.size(), 0);
  s.crossing.assign(model.edges.size(), kNoCrossing);
  if (model.material.plastic.yieldStress > 0.0) {
    s.plasticInverse.assign(model.mesh.tets.size(), Eigen::Matrix3d::Identity());
    s.plasticStrain.assign(model.mesh.tets.size(), 0.0);
  }
  for (const Collider& c : model.colliders) s.colliders.push_back(initialColliderState(c));
  return s;
}

EdgeDamage tetDamage(const SimModel& model, const std::vector<std::uint8_t>& damaged, int tet,
                     bool compressionResists) {
  EdgeDamage d;
  d.compressionResists = compressionResists;
  for (int e = 0; e < 6; ++e) {
    if (damaged[model.tetEdges[tet][e]]) d.intact &= static_cast<std::uint8_t>(~(1u << e));
  }
  return d;
}

int countDamagePieces(const SimModel& model, const SimState& state) {
  UnionFind uf(model.numVertices());
  int pieces = model.numVertices();
  for (int e = 0; e < model.numEdges(); ++e) {
    if (!state.damaged[e]) pieces -= uf.unite(model.edges[e][0], model.edges[e][1]);
  }
  return pieces;
}

}  // namespace galsculpt
